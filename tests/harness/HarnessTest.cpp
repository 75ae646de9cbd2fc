// The experiment harness of the frame-level benchmarks (benchmarks/harness): its command line
// refuses what it should before anything runs, a report quotes the command without its outputs,
// the table writes CSV as a stream writes numbers, and a variant that saw another state is named.

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "throng/bench/Experiment.h"
#include "throng/bench/ResultTable.h"
#include "throng/bench/SameState.h"

using namespace throng;
using namespace throng::bench;

namespace {

// Parses `args` (after the program name) for an experiment taking the common options `options`.
std::optional<int> parse(Experiment& e, std::vector<std::string> args) {
    args.insert(args.begin(), e.program());
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    return e.parse(int(argv.size()), argv.data());
}

const unsigned kMost = kActorList | kFrames | kWarmup | kImageSize | kCsv | kMarkdown;

}  // namespace

TEST(Harness, DefaultsHoldUntilAnOptionIsGivenAndTheActorCountsAreAList) {
    Experiment e("bench_test", "a test", kMost, {.actors = {10}, .frames = 3});
    ASSERT_FALSE(parse(e, {"--actors", "100,200", "--warmup", "7"}).has_value());
    EXPECT_EQ(e.spec().actors, (std::vector<std::int64_t>{100, 200}));
    EXPECT_EQ(e.spec().frames, 3);
    EXPECT_EQ(e.spec().warmup, 7);
}

TEST(Harness, ABadOrRepeatedOptionStopsBeforeAnythingRuns) {
    for (const std::vector<std::string>& bad : std::vector<std::vector<std::string>>{
             {"--frames", "0"}, {"--frames", "2", "--frames", "3"}, {"--width", "8"}, {"--bogus"}, {"--actors", "-5"},
             {"--csv", "/no/such/folder/rows.csv"}, {"--markdown", "."}}) {
        Experiment e("bench_test", "a test", kMost, {});
        EXPECT_EQ(parse(e, bad), Experiment::kUsageError) << bad.front();
    }
}

TEST(Harness, AnExperimentsOwnNumbersRefuseNaNAndInfinity) {
    for (const char* value : {"nan", "inf", "-1", "2", "x"}) {
        double share = 0.5;
        Experiment e("bench_test", "a test", 0, {});
        e.app().add_option("--share", share)->check(finiteNumber(0.0, 1.0));
        EXPECT_EQ(parse(e, {"--share", value}), Experiment::kUsageError) << value;
    }
}

TEST(Harness, TheReportQuotesTheCommandWithoutItsOutputs) {
    Experiment e("bench_test", "a test", kMost, {});
    std::string demands;
    e.app().add_option("--demands", demands);
    e.markOutput("--demands");
    ASSERT_FALSE(parse(e, {"--frames", "4", "--csv", "rows.csv", "--markdown=report.md", "--demands", "d.csv", "--warmup", "1"}).has_value());
    EXPECT_EQ(e.reproduction(), "bench_test --frames 4 --warmup 1");
}

TEST(Harness, TheTableWritesCsvAsAStreamDoesAndMarkdownByColumnFormat) {
    ResultTable t({{"actors", "actors", "%lld"}, {"method", "method", "%s", true}, {"ms", "", "%g"}, {"", "ms", "%.1f"}});
    t.add({std::int64_t(1000000), "actor", 0.1234567, 0.1234567});
    EXPECT_EQ(t.csv(), "actors,method,ms\n1000000,actor,0.123457\n") << "whole numbers stay whole, doubles get six digits";
    EXPECT_EQ(t.markdown(), "| actors | method | ms |\n|---:|---|---:|\n| 1000000 | actor | 0.1 |\n");
    EXPECT_THROW(t.add({std::int64_t(1)}), std::invalid_argument);
}

TEST(Harness, AVariantThatSawAnotherStateIsNamedWithItsTick) {
    std::vector<std::uint64_t> seen{7, 7, 8};
    std::vector<std::size_t> order;
    try {
        runOnSameStates(3, 1, [&](std::size_t v) { order.push_back(v); }, [&](std::size_t v) { return seen[v]; },
                        [](std::size_t v) { return "variant " + std::to_string(v); });
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), "tick 1: 'variant 2' saw another state");
    }
    // Tick 1: variant 1 goes first and sets the state; variant 2 differs and stops the tick there.
    EXPECT_EQ(order, (std::vector<std::size_t>{1, 2}));
}

TEST(Harness, AFileIsWrittenWholeOrNotAtAll) {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / "throng-harness-test";
    std::filesystem::create_directories(dir);
    const std::string path = (dir / "out.csv").string();
    writeWhole(path, "a,b\n1,2\n");
    std::ifstream in(path);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text, "a,b\n1,2\n");
    EXPECT_FALSE(std::filesystem::exists(path + ".part"));
    EXPECT_THROW(writeWhole((dir / "no-such-folder" / "out.csv").string(), "x"), std::runtime_error);
    std::filesystem::remove_all(dir);
}
