// sim::Ranks: run plainly it is one rank; run by CTest under mpiexec (label mpi) every rank runs
// these same tests in the same order, so each collective call below is made by all of them.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>

#include "throng/sim/Ranks.h"

namespace throng::sim {
namespace {

// A record as a simulation would send one: who sent it, to whom, and a payload.
struct Record {
    std::int32_t from = 0, to = 0;
    std::uint32_t index = 0;
    float x = 0.0f;
};

// How many records rank `from` sends rank `to` (none for some pairs, so empty messages travel too).
std::uint32_t recordCount(int from, int to) { return static_cast<std::uint32_t>((from * 7 + to * 3) % 5); }

TEST(Ranks, OneRankWithoutALauncher) {
    if (Ranks::launchedByMpi()) GTEST_SKIP() << "started by an MPI launcher";
    Ranks ranks;
    EXPECT_EQ(ranks.rank(), 0);
    EXPECT_EQ(ranks.size(), 1);
    const Bytes mine{std::byte{1}, std::byte{2}};
    const std::vector<Bytes> out{mine};
    EXPECT_EQ(ranks.exchange(out, 1, "self"), out);
    EXPECT_EQ(ranks.gather(mine, 2, "self"), out);
    EXPECT_EQ(ranks.broadcast(mine, 3, "self"), mine);
    EXPECT_EQ(ranks.bytesSent(), 0u);
}

TEST(Ranks, ExchangeDeliversEveryRanksRecords) {
    Ranks ranks;
    std::vector<Bytes> out(static_cast<std::size_t>(ranks.size()));
    for (int to = 0; to < ranks.size(); ++to) {
        std::vector<Record> records;
        for (std::uint32_t k = 0; k < recordCount(ranks.rank(), to); ++k)
            records.push_back({ranks.rank(), to, k, static_cast<float>(ranks.rank() * 100 + to) + 0.5f * static_cast<float>(k)});
        out[static_cast<std::size_t>(to)] = packRecords<Record>(records);
    }
    for (int round = 0; round < 3; ++round) {  // the same tag again: messages keep their order
        const std::vector<Bytes> in = ranks.exchange(out, 10, "records");
        ASSERT_EQ(in.size(), out.size());
        for (int from = 0; from < ranks.size(); ++from) {
            const auto records = unpackRecords<Record>(in[static_cast<std::size_t>(from)], from, "records");
            ASSERT_EQ(records.size(), recordCount(from, ranks.rank())) << "from rank " << from;
            for (std::uint32_t k = 0; k < records.size(); ++k) {
                EXPECT_EQ(records[k].from, from);
                EXPECT_EQ(records[k].to, ranks.rank());
                EXPECT_EQ(records[k].index, k);
                EXPECT_EQ(records[k].x, static_cast<float>(from * 100 + ranks.rank()) + 0.5f * static_cast<float>(k));
            }
        }
    }
}

TEST(Ranks, GatherCollectsOnRankZeroAllGatherAndBroadcastReachAll) {
    Ranks ranks;
    const std::vector<Record> mine(static_cast<std::size_t>(ranks.rank() + 1), Record{ranks.rank(), 0, 7, 1.5f});
    const std::vector<Bytes> all = ranks.gather(packRecords<Record>(mine), 11, "draw records");
    if (ranks.rank() == 0) {
        ASSERT_EQ(all.size(), static_cast<std::size_t>(ranks.size()));
        for (int r = 0; r < ranks.size(); ++r) {
            const auto records = unpackRecords<Record>(all[static_cast<std::size_t>(r)], r, "draw records");
            ASSERT_EQ(records.size(), static_cast<std::size_t>(r + 1));
            EXPECT_EQ(records.back().from, r);
        }
    } else {
        EXPECT_TRUE(all.empty());
    }
    // Every rank gets every rank's message, its own included.
    const std::vector<Bytes> everyone = ranks.allGather(packRecords<Record>(mine), 13, "walkers near the view");
    ASSERT_EQ(everyone.size(), static_cast<std::size_t>(ranks.size()));
    for (int r = 0; r < ranks.size(); ++r) {
        const auto records = unpackRecords<Record>(everyone[static_cast<std::size_t>(r)], r, "walkers near the view");
        ASSERT_EQ(records.size(), static_cast<std::size_t>(r + 1));
        EXPECT_EQ(records.back().from, r);
    }
    const std::vector<Record> camera{{0, 0, 42, 3.25f}};
    const Bytes sent = ranks.rank() == 0 ? packRecords<Record>(camera) : Bytes{};
    const auto got = unpackRecords<Record>(ranks.broadcast(sent, 12, "camera"), 0, "camera");
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].index, 42u);
    EXPECT_EQ(got[0].x, 3.25f);
}

TEST(Ranks, RefusesBadArguments) {
    Ranks ranks;
    const std::vector<Bytes> tooMany(static_cast<std::size_t>(ranks.size() + 1));
    EXPECT_THROW(ranks.exchange(tooMany, 13, "bad"), std::invalid_argument);
    const std::vector<Bytes> right(static_cast<std::size_t>(ranks.size()));
    EXPECT_THROW(ranks.exchange(right, -1, "bad"), std::invalid_argument);
    EXPECT_THROW(ranks.exchange(right, 10000, "bad"), std::invalid_argument);
    EXPECT_THROW(ranks.setTimeout(std::chrono::milliseconds(0)), std::invalid_argument);
    const Bytes odd(sizeof(Record) + 3);
    try {
        unpackRecords<Record>(odd, 1, "ghosts");
        FAIL() << "a partial record was read";
    } catch (const RankError& e) {
        EXPECT_EQ(e.rank(), 1);
        EXPECT_NE(std::string(e.what()).find("ghosts"), std::string::npos) << e.what();
    }
}

// Last: the silent rank leaves messages it never reads (under a tag no other test uses).
TEST(Ranks, SilentRankIsNamedWithinTheTimeout) {
    Ranks ranks(std::chrono::milliseconds(400));
    if (ranks.size() < 2) GTEST_SKIP() << "needs two ranks (run under mpiexec, label mpi)";
    const int silent = ranks.size() - 1;
    if (ranks.rank() == silent) return;  // as a rank that hangs would: it never calls
    const std::vector<Bytes> out(static_cast<std::size_t>(ranks.size()), Bytes(16));
    const auto start = std::chrono::steady_clock::now();
    try {
        ranks.exchange(out, 9999, "ghost exchange");
        FAIL() << "the exchange completed without rank " << silent;
    } catch (const RankError& e) {
        EXPECT_EQ(e.rank(), silent);
        const std::string message = e.what();
        EXPECT_NE(message.find("rank " + std::to_string(silent)), std::string::npos) << message;
        EXPECT_NE(message.find("ghost exchange"), std::string::npos) << message;
    }
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
}

}  // namespace
}  // namespace throng::sim
