// The frame-budget allocator on synthetic frame times (it picks the most accurate rung that fits,
// comes back under budget at once after a spike, does not oscillate around a rung that does not
// fit, is deterministic), and its ladder file (read back, refused with file and line when bad).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <stdexcept>
#include <vector>

#include "throng/sim/AccuracyCsv.h"
#include "throng/sim/BudgetLadder.h"
#include "throng/sim/FrameBudgetAllocator.h"

using namespace throng::sim;

namespace {

std::string outputPath(const std::string& name) {
    std::filesystem::create_directories(THRONG_TEST_OUTPUT_DIR);
    return std::string(THRONG_TEST_OUTPUT_DIR) + "/" + name;
}

// A ladder with these measured times (most accurate and dearest first), errors rising.
std::vector<BudgetRung> ladderOf(const std::vector<double>& ms) {
    std::vector<BudgetRung> ladder;
    for (std::size_t i = 0; i < ms.size(); ++i) {
        BudgetRung r;
        r.settings.lodScale = 1.0 + double(i);
        r.settings.impostorDistance = 80.0 / double(i + 1);
        r.settings.keyPoseDistance = 40.0 / double(i + 1);
        r.settings.morphBudget = int(ms.size() - i);
        r.error = 0.01 * double(i);
        r.ms = ms[i];
        ladder.push_back(r);
    }
    return ladder;
}

FrameBudgetOptions budgetOf(double ms) {
    FrameBudgetOptions o;
    o.budgetMs = ms;
    return o;
}

// Runs `frames` frames, each costing cost(frame, rung) for the rung the allocator chose (no
// pipeline: a frame is observed before the next is prepared). Returns the rungs used, in order.
std::vector<int> run(FrameBudgetAllocator& a, int frames, const std::function<double(int, int)>& cost) {
    std::vector<int> rungs;
    for (int f = 0; f < frames; ++f) {
        const int rung = a.rung();
        rungs.push_back(rung);
        a.observe(rung, cost(f, rung));
    }
    return rungs;
}

}  // namespace

TEST(FrameBudget, StartsAtTheMostAccurateRungTheLadderSaysFits) {
    const auto ladder = ladderOf({400, 200, 100, 50});
    EXPECT_EQ(FrameBudgetAllocator(ladder, budgetOf(150)).rung(), 2);   // 100 <= 0.85 * 150
    EXPECT_EQ(FrameBudgetAllocator(ladder, budgetOf(1000)).rung(), 0);
    EXPECT_EQ(FrameBudgetAllocator(ladder, budgetOf(10)).rung(), 3);    // nothing fits: the cheapest
}

TEST(FrameBudget, ClimbsToTheMostAccurateRungThatFitsAndStaysThere) {
    const std::vector<double> ms{400, 200, 100, 50};
    FrameBudgetAllocator a(ladderOf(ms), budgetOf(150));
    // The machine is twice as fast as the ladder says: rung 1 (100 ms) fits, rung 0 (200 ms) does not.
    const std::vector<int> rungs = run(a, 300, [&](int, int r) { return 0.5 * ms[std::size_t(r)]; });
    EXPECT_EQ(rungs.front(), 2);
    EXPECT_EQ(rungs.back(), 1);
    for (int r : rungs) EXPECT_GE(r, 1) << "rung 0 costs 200 ms against a budget of 150";
    EXPECT_EQ(a.framesOver(), 0);
    EXPECT_EQ(a.changes(), 1);
    // Hysteresis: not before upFrames comfortable frames.
    for (int f = 0; f < a.options().upFrames - 1; ++f) EXPECT_EQ(rungs[std::size_t(f)], 2) << "frame " << f;
    EXPECT_NEAR(a.measuredMs(1), 100.0, 1e-9);
}

TEST(FrameBudget, ClimbsSeveralRungsAtOnceWhenTheLoadGoes) {
    const std::vector<double> ms{400, 300, 200, 100, 50};
    FrameBudgetOptions o = budgetOf(150);
    o.startRung = 4;
    FrameBudgetAllocator a(ladderOf(ms), o);
    // Loaded at first (twice the ladder: rung 4 only), then a third of the ladder: rung 1 (100 ms)
    // fits under 0.75 * 150, rung 0 (133 ms) does not.
    const std::vector<int> rungs = run(a, 200, [&](int f, int r) { return (f < 50 ? 2.0 : 1.0 / 3.0) * ms[std::size_t(r)]; });
    EXPECT_EQ(rungs[49], 4);
    for (int f = 50; f < 50 + a.options().upFrames; ++f) EXPECT_EQ(rungs[std::size_t(f)], 4) << "frame " << f << ": before upFrames comfortable frames";
    std::vector<int> visited;
    for (int r : rungs)
        if (visited.empty() || visited.back() != r) visited.push_back(r);
    EXPECT_EQ(visited, (std::vector<int>{4, 1})) << "straight to the most accurate rung that fits";
    EXPECT_EQ(a.framesOver(), 0);
}

TEST(FrameBudget, StaysUnderBudgetAfterASpike) {
    const std::vector<double> ms{400, 200, 100, 50};
    FrameBudgetAllocator a(ladderOf(ms), budgetOf(150));
    // Twice as fast as the ladder, but frames 100..159 are three times as dear (another program
    // takes the cores); rung 3 stays under the budget even then (75 ms).
    auto load = [](int f) { return f >= 100 && f < 160 ? 1.5 : 0.5; };
    const std::vector<int> rungs = run(a, 400, [&](int f, int r) { return load(f) * ms[std::size_t(r)]; });
    ASSERT_EQ(rungs[99], 1);
    EXPECT_EQ(rungs[101], 3) << "one frame over the budget: down at once to the rung predicted to fit";
    int over = 0;
    for (int f = 0; f < 400; ++f) over += load(f) * ms[std::size_t(rungs[std::size_t(f)])] > 150 ? 1 : 0;
    EXPECT_EQ(over, 1) << "only the frame of the spike itself";
    EXPECT_EQ(a.framesOver(), 1);
    EXPECT_EQ(rungs.back(), 1) << "the load gone, the most accurate rung that fits again";
}

TEST(FrameBudget, HysteresisPreventsOscillation) {
    // The ladder says rung 1 costs 100 ms, but here it costs 160 (over a 150 ms budget) while the
    // others cost what the ladder says: each try of rung 1 fails at once.
    const std::vector<double> ladderMs{400, 100, 80, 40}, actual{400, 160, 80, 40};
    FrameBudgetAllocator a(ladderOf(ladderMs), budgetOf(150));
    const std::vector<int> rungs = run(a, 2000, [&](int, int r) { return actual[std::size_t(r)]; });
    int tries = 0;
    for (std::size_t f = 1; f < rungs.size(); ++f) tries += rungs[f] == 1 && rungs[f - 1] != 1 ? 1 : 0;
    // Each failed try doubles the wait (20, 40, ... 640 frames): 6 tries in 2000 frames, where a
    // fixed wait of 20 frames would try about 95 times.
    EXPECT_GE(tries, 2);
    EXPECT_LE(tries, 7);
    EXPECT_LE(a.framesOver(), tries + 1) << "each try, and the first frame (the ladder says rung 1 fits)";
    EXPECT_LE(double(a.framesOver()) / 2000.0, 0.05);
}

TEST(FrameBudget, DeterministicForTheSameFrameTimes) {
    const std::vector<double> ms{400, 200, 100, 50};
    // A load that comes and goes, with jitter: the allocator moves, the same way each time.
    auto noisy = [&](int f, int r) { return ms[std::size_t(r)] * (0.3 + 0.9 * std::fabs(std::sin(0.01 * f)) + 0.1 * std::sin(1.7 * f)); };
    FrameBudgetAllocator a(ladderOf(ms), budgetOf(150)), b(ladderOf(ms), budgetOf(150));
    const auto ra = run(a, 1500, noisy), rb = run(b, 1500, noisy);
    EXPECT_EQ(ra, rb);
    EXPECT_GE(a.changes(), 3);
    EXPECT_EQ(a.changes(), b.changes());
}

TEST(FrameBudget, PipelinedFrameOfTheOldRungDoesNotStepDownAgain) {
    // With a pipeline the frame measured after a step down was prepared at the old rung.
    const std::vector<double> ms{400, 200, 100, 50};
    FrameBudgetAllocator a(ladderOf(ms), budgetOf(250));
    ASSERT_EQ(a.rung(), 1);
    EXPECT_EQ(a.observe(1, 260), 2);  // over: down to rung 2 (predicted 130 <= 212.5)
    EXPECT_EQ(a.observe(1, 200), 2) << "the old rung's next frame, under the budget, says nothing of rung 2";
    EXPECT_EQ(a.observe(2, 100), 2);
}

TEST(FrameBudget, RefusesBadSettings) {
    const auto ladder = ladderOf({400, 200});
    EXPECT_THROW(FrameBudgetAllocator({}, budgetOf(100)), std::invalid_argument);
    EXPECT_THROW(FrameBudgetAllocator(ladder, budgetOf(0)), std::invalid_argument);
    EXPECT_THROW(FrameBudgetAllocator(ladder, budgetOf(-5)), std::invalid_argument);
    EXPECT_THROW(FrameBudgetAllocator(ladder, budgetOf(std::nan(""))), std::invalid_argument);
    EXPECT_THROW(FrameBudgetAllocator(ladder, budgetOf(std::numeric_limits<double>::infinity())), std::invalid_argument);
    FrameBudgetOptions start = budgetOf(100);
    start.startRung = 2;
    EXPECT_THROW(FrameBudgetAllocator(ladder, start), std::invalid_argument);
    FrameBudgetAllocator a(ladder, budgetOf(100));
    EXPECT_THROW(a.observe(0, std::nan("")), std::invalid_argument);
    EXPECT_THROW(a.observe(0, -1.0), std::invalid_argument);
    EXPECT_THROW(a.observe(2, 10.0), std::invalid_argument);
    auto zero = ladder;
    zero[1].ms = 0;
    EXPECT_THROW(FrameBudgetAllocator(zero, budgetOf(100)), std::invalid_argument);
}

TEST(FrameBudgetLadder, RungValueRoundTrips) {
    BudgetSettings s{0.75, 80, 40, 8};
    const BudgetSettings back = parseBudgetRungValue(budgetRungValue(s));
    EXPECT_EQ(back.lodScale, 0.75);
    EXPECT_EQ(back.impostorDistance, 80);
    EXPECT_EQ(back.keyPoseDistance, 40);
    EXPECT_EQ(back.morphBudget, 8);
    EXPECT_THROW(parseBudgetRungValue("lod-scale=1 impostor-distance=40 key-pose-distance=20"), std::invalid_argument);  // missing
    EXPECT_THROW(parseBudgetRungValue("lod-scale=0 impostor-distance=40 key-pose-distance=20 morph-budget=2"), std::invalid_argument);
    EXPECT_THROW(parseBudgetRungValue("lod-scale=1 impostor-distance=-1 key-pose-distance=20 morph-budget=2"), std::invalid_argument);
    EXPECT_THROW(parseBudgetRungValue("lod-scale=nan impostor-distance=40 key-pose-distance=20 morph-budget=2"), std::invalid_argument);
    EXPECT_THROW(parseBudgetRungValue("lod-scale=1 impostor-distance=40 key-pose-distance=20 morph-budget=2.5"), std::invalid_argument);
    EXPECT_THROW(parseBudgetRungValue("lod-scale=1 lod-scale=1 impostor-distance=40 key-pose-distance=20 morph-budget=2"), std::invalid_argument);
    EXPECT_THROW(parseBudgetRungValue("lod-scale=1 impostor-distance=40 key-pose-distance=20 morph-budget=2 speed=3"), std::invalid_argument);
    // The render scale: 1 when left out (ladders written before it), else written and read back.
    EXPECT_EQ(back.renderScale, 1.0);
    EXPECT_EQ(budgetRungValue(s).find("render-scale"), std::string::npos);
    s.renderScale = 0.5;
    EXPECT_EQ(parseBudgetRungValue(budgetRungValue(s)).renderScale, 0.5);
    EXPECT_EQ(back.townLodScale, 0.0);
    s.townLodScale = 2.0;
    EXPECT_EQ(parseBudgetRungValue(budgetRungValue(s)).townLodScale, 2.0);
    EXPECT_THROW(parseBudgetRungValue("lod-scale=1 impostor-distance=40 key-pose-distance=20 morph-budget=2 town-lod-scale=0"),
                 std::invalid_argument);
    for (const char* bad : {"0", "1.5", "-0.5", "nan"})
        EXPECT_THROW(parseBudgetRungValue(std::string("lod-scale=1 impostor-distance=40 key-pose-distance=20 morph-budget=2 render-scale=") + bad),
                     std::invalid_argument) << bad;
}

TEST(FrameBudgetLadder, ReadsWhatBenchBudgetWrites) {
    const std::string path = outputPath("ladder.csv");
    {
        AccuracyCsv csv(path);
        const auto ladder = ladderOf({300, 150, 75});
        for (const BudgetRung& r : ladder) {
            AccuracyRecord rec;
            rec.knob = kBudgetRungKnob;
            rec.value = budgetRungValue(r.settings);
            rec.metrics = {{"pixels_off_8", r.error, "share", true}, {"psnr", 40 - r.error, "dB", false}, {"ssim", 0.99, "1", false}};
            rec.ms = r.ms;
            rec.msPhase = "app_cull_draw";
            rec.scene = "default.json";
            rec.camera = "path";
            rec.actors = 10000;
            csv.add(rec);
        }
    }
    const std::vector<BudgetRung> back = readBudgetLadder(path);
    ASSERT_EQ(back.size(), 3u);
    EXPECT_EQ(back[1].ms, 150);
    EXPECT_EQ(back[2].settings.lodScale, 3.0);
    EXPECT_NEAR(back[2].error, 0.02, 1e-12);
    EXPECT_NEAR(back[2].psnr, 39.98, 1e-9);
}

TEST(FrameBudgetLadder, BadLadderRefusedWithFileAndLine) {
    const std::string head = std::string(AccuracyCsv::header()) + "\n";
    const std::string good = "frame budget rung,lod-scale=1 impostor-distance=40 key-pose-distance=20 morph-budget=2,0,pixels_off_8,0.01,share,lower,100,app_cull_draw,0,default.json,path,10000\n";
    auto refused = [&](const std::string& name, const std::string& text, const std::string& expected) {
        const std::string path = outputPath(name);
        std::ofstream(path) << text;
        try {
            readBudgetLadder(path);
            ADD_FAILURE() << name << ": accepted";
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << name << ": " << e.what();
        }
    };
    refused("missing.csv", "", "missing.csv");
    refused("not-accuracy.csv", "a,b,c\n", "not-accuracy.csv:1");
    refused("no-rungs.csv", head + "lod scale,1,0,psnr,40,dB,higher,10,draw,0,default.json,path,10\n", "no 'frame budget rung' rows");
    refused("bad-value.csv", head + good + "frame budget rung,lod-scale=2 speed=1,0,pixels_off_8,0.02,share,lower,50,app_cull_draw,0,default.json,path,10000\n",
            "bad-value.csv:3: rung 'lod-scale=2 speed=1': unknown key 'speed'");
    refused("bad-number.csv", head + "frame budget rung,lod-scale=1 impostor-distance=40 key-pose-distance=20 morph-budget=2,0,pixels_off_8,x,share,lower,100,app_cull_draw,0,default.json,path,10000\n",
            "bad-number.csv:2");
    refused("no-error.csv", head + "frame budget rung,lod-scale=1 impostor-distance=40 key-pose-distance=20 morph-budget=2,0,psnr,40,dB,higher,100,app_cull_draw,0,default.json,path,10000\n",
            "no-error.csv:2: rung 'lod-scale=1 impostor-distance=40 key-pose-distance=20 morph-budget=2' has no pixels_off_8 line");
    refused("unordered.csv", head + good + "frame budget rung,lod-scale=2 impostor-distance=20 key-pose-distance=10 morph-budget=1,0,pixels_off_8,0.001,share,lower,50,app_cull_draw,0,default.json,path,10000\n",
            "unordered.csv:3: rung 'lod-scale=2 impostor-distance=20 key-pose-distance=10 morph-budget=1' errs less than the rung before it");
    refused("zero-ms.csv", head + "frame budget rung,lod-scale=1 impostor-distance=40 key-pose-distance=20 morph-budget=2,0,pixels_off_8,0.01,share,lower,0,app_cull_draw,0,default.json,path,10000\n",
            "zero-ms.csv:2: rung");
}
