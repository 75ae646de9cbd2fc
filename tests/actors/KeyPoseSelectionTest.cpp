// The key-pose cache of seed 004 on the CPU: which poses to cache (the greedy selection of §4.2 and
// the exact one of §4.1, checked against each other, against the paper's worked example and against
// an exhaustive search), the rows kept from frame to frame (retention, least recently used
// replacement), and the key-poses of a template (sampling in both modes, palettes); demands of
// several processes added, and rows copied from the process that selected.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "throng/testkit/ActorTestScenes.h"
#include "throng/actors/ActorTemplate.h"
#include "throng/actors/AnimationClip.h"
#include "throng/actors/KeyPoseArbiter.h"
#include "throng/actors/KeyPoseCache.h"
#include "throng/research/KeyPoseExactSelection.h"
#include "throng/actors/KeyPoseRows.h"
#include "throng/actors/KeyPoseSelection.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/MeshShapes.h"

using namespace throng;

namespace {

// Expects `f` to throw E with a message containing `text`.
template <class E, class F>
void expectThrowWith(F&& f, const std::string& text) {
    try {
        f();
        ADD_FAILURE() << "no exception; expected one mentioning '" << text << "'";
    } catch (const E& e) {
        EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
}

// Demands of characters between successive key-poses of one clip: bin i needs poses i and i + 1.
std::vector<KeyPoseDemand> bins(const std::vector<std::uint32_t>& counts) {
    std::vector<KeyPoseDemand> d;
    for (std::uint32_t i = 0; i < counts.size(); ++i) d.push_back({i, i + 1, counts[i]});
    return d;
}

std::set<std::uint32_t> asSet(const std::vector<std::uint32_t>& v) { return {v.begin(), v.end()}; }

// A Figure 7 instance: `characters` actors, each with a source key-pose drawn from a normal
// distribution over `poses` key-poses and a destination that is the next pose (probability
// `nextPose`) or another normal draw (never the source); `intermittent`: the source alone.
std::vector<KeyPoseDemand> randomDemand(std::uint32_t seed, std::uint32_t characters, std::uint32_t poses, double nextPose,
                                        bool intermittent = false) {
    std::mt19937 rng(seed);
    const auto unit = [&] { return (static_cast<double>(rng()) + 0.5) / 4294967296.0; };  // in (0, 1)
    const auto normalPose = [&] {
        // Box-Muller, mean in the middle, three standard deviations to either end.
        const double u1 = unit(), u2 = unit();
        const double z = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
        const double x = std::round((poses - 1) / 2.0 + z * poses / 6.0);
        return static_cast<std::uint32_t>(std::clamp(x, 0.0, static_cast<double>(poses - 1)));
    };
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> count;
    for (std::uint32_t c = 0; c < characters; ++c) {
        const std::uint32_t a = normalPose();
        std::uint32_t b = a;
        if (!intermittent) {
            if (unit() < nextPose) b = (a + 1) % poses;
            else
                while (b == a) b = normalPose();
        }
        ++count[{std::min(a, b), std::max(a, b)}];
    }
    std::vector<KeyPoseDemand> d;
    for (const auto& [pair, n] : count) d.push_back({pair.first, pair.second, n});
    return d;
}

// The optimum by trying every set of `capacity` candidate poses (independent of GLPK).
std::uint64_t bruteForceServed(const std::vector<KeyPoseDemand>& demand, std::uint32_t capacity) {
    std::vector<std::uint32_t> candidates;
    for (const KeyPoseDemand& d : demand) candidates.push_back(d.a), candidates.push_back(d.b);
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    const std::size_t n = candidates.size();
    if (n > 24) throw std::logic_error("bruteForceServed: too many candidates");
    const auto bit = [&](std::uint32_t pose) {
        return std::uint32_t{1} << (std::lower_bound(candidates.begin(), candidates.end(), pose) - candidates.begin());
    };
    std::vector<std::pair<std::uint32_t, std::uint32_t>> needs;
    for (const KeyPoseDemand& d : demand) needs.push_back({bit(d.a) | bit(d.b), d.actors});
    const std::uint32_t k = std::min<std::uint32_t>(capacity, static_cast<std::uint32_t>(n));
    std::uint64_t best = 0;
    const auto evaluate = [&](std::uint32_t mask) {
        std::uint64_t served = 0;
        for (const auto& [need, actors] : needs)
            if ((mask & need) == need) served += actors;
        best = std::max(best, served);
    };
    if (k == 0) return 0;
    // Every k-subset of n bits, in increasing order (Gosper's hack).
    for (std::uint32_t mask = (std::uint32_t{1} << k) - 1; mask < (std::uint32_t{1} << n);) {
        evaluate(mask);
        const std::uint32_t c = mask & (~mask + 1), r = mask + c;
        mask = (((r ^ mask) >> 2) / c) | r;
    }
    return best;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Seed 004 §4.2's worked example: 14 characters, one clip of 7 key-poses (0.0 .. 1.2), a cache of 4.

TEST(KeyPoseSelection, PaperExampleGreedyRetentionAndExact) {
    constexpr std::uint32_t characters = 14, capacity = 4;
    KeyPoseRows rows(capacity, 7);
    // Time t (Figure 5): bins 0 and 2 are the largest; bin 1 finds both its poses, bin 3 one, bin 4 none.
    const std::vector<KeyPoseDemand> t = bins({5, 2, 4, 1, 2, 0});
    const std::vector<std::uint32_t> chosenT = selectKeyPosesGreedy(t, capacity, rows.held());
    EXPECT_EQ(asSet(chosenT), (std::set<std::uint32_t>{0, 1, 2, 3}));  // key-poses 0.0, 0.2, 0.4, 0.6
    const std::uint64_t servedT = actorsServed(t, chosenT);
    EXPECT_EQ(servedT, 11u);
    const std::uint32_t updatesT = rows.hold(chosenT, 1);
    EXPECT_EQ(updatesT, 4u);
    EXPECT_EQ(updatesT + (characters - servedT), 7u);  // 4 cache updates + 3 skinned characters

    // Time t + dt (Figure 6): everyone one bin on, bins 1 and 3 the largest: {0.2, 0.4, 0.6, 0.8}.
    const std::vector<KeyPoseDemand> next = bins({0, 5, 2, 4, 1, 2});
    const std::vector<std::uint32_t> held = rows.held();
    const std::vector<std::uint32_t> chosenNext = selectKeyPosesGreedy(next, capacity, held);
    EXPECT_EQ(asSet(chosenNext), (std::set<std::uint32_t>{1, 2, 3, 4}));
    const std::uint64_t servedNext = actorsServed(next, chosenNext);
    EXPECT_EQ(servedNext, 11u);
    const std::uint32_t row0 = rows.rowOf(0);
    const std::uint32_t updatesNext = rows.hold(chosenNext, 2);
    EXPECT_EQ(updatesNext, 1u);                                   // only 0.8 is skinned into the cache
    EXPECT_EQ(rows.rowOf(0), KeyPoseRows::kNone);                  // it replaced 0.0, the least recently used
    EXPECT_EQ(rows.rowOf(4), row0);
    EXPECT_EQ(updatesNext + (characters - servedNext), 4u);        // 1 update + 3 skinned characters

    // The exact selection finds no better, and with the rows held it also needs one update.
    const KeyPoseExactResult exactT = selectKeyPosesExact(t, capacity);
    EXPECT_TRUE(exactT.optimal());
    EXPECT_EQ(exactT.served, 11u);
    EXPECT_EQ(exactT.poses, (std::vector<std::uint32_t>{0, 1, 2, 3}));
    const KeyPoseExactResult exactNext = selectKeyPosesExact(next, capacity, held);
    EXPECT_TRUE(exactNext.optimal());
    EXPECT_EQ(exactNext.served, 11u);
    EXPECT_EQ(exactNext.updates, 1u);
    EXPECT_EQ(exactNext.bound, 11u);
}

TEST(KeyPoseSelection, GreedySkipsDemandsThatDoNotFitAndPrefersResidentPosesOnTies) {
    // {2, 3} no longer fits after {0, 1}; the paper's text would stop there, the greedy selection
    // goes on to {4}, which does.
    const std::vector<KeyPoseDemand> demand = {{0, 1, 5}, {2, 3, 4}, {4, 4, 3}};
    const std::vector<std::uint32_t> chosen = selectKeyPosesGreedy(demand, 3);
    EXPECT_EQ(chosen, (std::vector<std::uint32_t>{0, 1, 4}));
    EXPECT_EQ(actorsServed(demand, chosen), 8u);
    // Equal demands: the one whose poses are resident first.
    const std::vector<KeyPoseDemand> tie = {{0, 1, 3}, {2, 3, 3}};
    EXPECT_EQ(asSet(selectKeyPosesGreedy(tie, 2)), (std::set<std::uint32_t>{0, 1}));
    EXPECT_EQ(asSet(selectKeyPosesGreedy(tie, 2, std::vector<std::uint32_t>{3, 2})), (std::set<std::uint32_t>{2, 3}));
    EXPECT_TRUE(selectKeyPosesGreedy(tie, 0).empty());
}

// ---------------------------------------------------------------------------------------------
// Random instances like seed 004's Figure 7: 30 characters, 22 key-poses, normally distributed.

TEST(KeyPoseSelection, ExactIsOptimalAndNeverBelowGreedyOnFigure7Instances) {
    constexpr std::uint32_t characters = 30, poses = 22;
    std::uint64_t greedyTotal = 0, exactTotal = 0;
    for (std::uint32_t seed = 1; seed <= 12; ++seed) {
        const std::vector<KeyPoseDemand> demand = randomDemand(seed, characters, poses, seed % 2 ? 0.5 : 0.0);
        for (std::uint32_t capacity = 1; capacity <= poses; ++capacity) {
            SCOPED_TRACE("seed " + std::to_string(seed) + ", capacity " + std::to_string(capacity));
            const std::vector<std::uint32_t> greedy = selectKeyPosesGreedy(demand, capacity);
            ASSERT_LE(greedy.size(), capacity);
            const std::uint64_t greedyServed = actorsServed(demand, greedy);
            const KeyPoseExactResult exact = selectKeyPosesExact(demand, capacity, {}, {.poseCount = poses});
            ASSERT_TRUE(exact.optimal());
            EXPECT_LE(exact.poses.size(), capacity);
            EXPECT_EQ(actorsServed(demand, exact.poses), exact.served);
            EXPECT_GE(exact.served, greedyServed);
            EXPECT_EQ(exact.bound, exact.served);
            EXPECT_EQ(exact.updates, exact.poses.size());  // nothing resident: every pose is an update
            if (seed <= 4) {
                EXPECT_EQ(exact.served, bruteForceServed(demand, capacity));
            }
            greedyTotal += greedyServed;
            exactTotal += exact.served;
        }
    }
    // Not vacuous: the greedy selection is not optimal everywhere on these instances.
    EXPECT_GT(exactTotal, greedyTotal);
}

TEST(KeyPoseSelection, GreedyIsOptimalForIntermittentDemands) {
    for (std::uint32_t seed = 1; seed <= 10; ++seed) {
        const std::vector<KeyPoseDemand> demand = randomDemand(seed, 30, 22, 0.0, true);
        for (const KeyPoseDemand& d : demand) ASSERT_EQ(d.a, d.b);
        for (std::uint32_t capacity = 1; capacity <= 22; ++capacity) {
            SCOPED_TRACE("seed " + std::to_string(seed) + ", capacity " + std::to_string(capacity));
            const KeyPoseExactResult exact = selectKeyPosesExact(demand, capacity);
            ASSERT_TRUE(exact.optimal());
            EXPECT_EQ(actorsServed(demand, selectKeyPosesGreedy(demand, capacity)), exact.served);
            EXPECT_EQ(exact.served, bruteForceServed(demand, capacity));
        }
    }
}

TEST(KeyPoseSelection, ExactPrefersResidentPosesOnlyOnTies) {
    // Two equally good pairs: the one already resident wins, with no update.
    const std::vector<KeyPoseDemand> tie = {{0, 1, 3}, {2, 3, 3}};
    const std::vector<std::uint32_t> resident = {3, 2};
    const KeyPoseExactResult kept = selectKeyPosesExact(tie, 2, resident);
    EXPECT_EQ(kept.poses, (std::vector<std::uint32_t>{2, 3}));
    EXPECT_EQ(kept.updates, 0u);
    EXPECT_EQ(kept.served, 3u);
    // One more actor on the other pair outweighs both updates.
    const std::vector<KeyPoseDemand> better = {{0, 1, 4}, {2, 3, 3}};
    const KeyPoseExactResult moved = selectKeyPosesExact(better, 2, resident);
    EXPECT_EQ(moved.poses, (std::vector<std::uint32_t>{0, 1}));
    EXPECT_EQ(moved.served, 4u);
    EXPECT_EQ(moved.updates, 2u);
    // On random instances with random resident poses: the same served count as without them, never
    // more updates than the selection made without them.
    std::mt19937 rng(7);
    for (std::uint32_t seed = 1; seed <= 6; ++seed) {
        const std::vector<KeyPoseDemand> demand = randomDemand(100 + seed, 30, 22, 0.5);
        std::vector<std::uint32_t> all(22);
        for (std::uint32_t i = 0; i < 22; ++i) all[i] = i;
        for (std::uint32_t capacity = 2; capacity <= 12; capacity += 2) {
            std::shuffle(all.begin(), all.end(), rng);
            const std::vector<std::uint32_t> held(all.begin(), all.begin() + capacity);
            const KeyPoseExactResult plain = selectKeyPosesExact(demand, capacity);
            const KeyPoseExactResult withHeld = selectKeyPosesExact(demand, capacity, held);
            ASSERT_TRUE(plain.optimal() && withHeld.optimal());
            EXPECT_EQ(withHeld.served, plain.served);
            std::uint32_t plainUpdates = 0;
            for (const std::uint32_t p : plain.poses) plainUpdates += std::find(held.begin(), held.end(), p) == held.end();
            EXPECT_LE(withHeld.updates, plainUpdates);
        }
    }
}

TEST(KeyPoseSelection, ExactHandlesTrivialAndMergedDemands) {
    const std::vector<KeyPoseDemand> demand = {{1, 2, 3}, {2, 1, 2}, {4, 4, 1}, {5, 6, 0}};
    // The same pair in either order is one demand of 5 actors; a demand of no actors is ignored.
    const KeyPoseExactResult two = selectKeyPosesExact(demand, 2);
    EXPECT_EQ(two.poses, (std::vector<std::uint32_t>{1, 2}));
    EXPECT_EQ(two.served, 5u);
    EXPECT_TRUE(two.optimal());
    // Capacity 0: nothing chosen, proven (no demand needs fewer than one pose).
    const KeyPoseExactResult none = selectKeyPosesExact(demand, 0);
    EXPECT_TRUE(none.poses.empty());
    EXPECT_EQ(none.served, 0u);
    EXPECT_TRUE(none.optimal());
    // Everything fits: every demanded pose, everyone served.
    const KeyPoseExactResult all = selectKeyPosesExact(demand, 3);
    EXPECT_EQ(all.poses, (std::vector<std::uint32_t>{1, 2, 4}));
    EXPECT_EQ(all.served, 6u);
    EXPECT_TRUE(all.optimal());
    // No demand at all.
    const KeyPoseExactResult empty = selectKeyPosesExact({}, 4);
    EXPECT_TRUE(empty.poses.empty() && empty.optimal());
}

TEST(KeyPoseSelection, ExactReportsTheLimitsThatStoppedIt) {
    const std::vector<KeyPoseDemand> demand = randomDemand(3, 30, 22, 0.5);
    // More demands than allowed: the greedy selection, not claimed optimal.
    const KeyPoseExactResult sized = selectKeyPosesExact(demand, 6, {}, {.maxDemands = 3});
    EXPECT_EQ(sized.status, KeyPoseExactStatus::SizeLimit);
    EXPECT_FALSE(sized.optimal());
    EXPECT_EQ(sized.served, actorsServed(demand, selectKeyPosesGreedy(demand, 6)));
    EXPECT_EQ(sized.bound, 30u);

    // A large instance (2000 actors on 400 poses, a cache of 120) with a millisecond: stopped by the
    // time limit, never below the greedy selection, with a bound above what it serves.
    std::mt19937 rng(11);
    std::uniform_int_distribution<std::uint32_t> pose(0, 399);
    std::vector<KeyPoseDemand> big;
    for (int i = 0; i < 2000; ++i) big.push_back({pose(rng), pose(rng), 1 + pose(rng) % 5});
    const KeyPoseExactResult timed = selectKeyPosesExact(big, 120, {}, {.timeLimitSeconds = 0.001});
    EXPECT_EQ(timed.status, KeyPoseExactStatus::TimeLimit);
    EXPECT_FALSE(timed.optimal());
    EXPECT_GE(timed.served, actorsServed(big, selectKeyPosesGreedy(big, 120)));
    EXPECT_EQ(actorsServed(big, timed.poses), timed.served);
    EXPECT_LE(timed.poses.size(), 120u);
    EXPECT_GT(timed.bound, timed.served);

    // A medium instance the solver proves in a fraction of a second, stopped after 20 ms: whatever
    // it found is between the greedy selection and the optimum, and its bound is a true bound.
    std::uniform_int_distribution<std::uint32_t> pose40(0, 39);
    std::vector<KeyPoseDemand> medium;
    for (int i = 0; i < 120; ++i) medium.push_back({pose40(rng), pose40(rng), 1 + pose40(rng) % 5});
    const KeyPoseExactResult proven = selectKeyPosesExact(medium, 10);
    ASSERT_TRUE(proven.optimal());
    const KeyPoseExactResult early = selectKeyPosesExact(medium, 10, {}, {.timeLimitSeconds = 0.02});
    EXPECT_GE(early.served, actorsServed(medium, selectKeyPosesGreedy(medium, 10)));
    EXPECT_LE(early.served, proven.served);
    EXPECT_GE(early.bound, proven.served);
    if (early.optimal()) {
        EXPECT_EQ(early.served, proven.served);  // a fast machine may prove it within the limit
    } else {
        EXPECT_EQ(early.status, KeyPoseExactStatus::TimeLimit);
    }
}

TEST(KeyPoseSelection, ExactRejectsBadInputNamingIt) {
    const std::vector<KeyPoseDemand> demand = {{0, 1, 2}, {1, 7, 1}};
    expectThrowWith<std::invalid_argument>([&] { selectKeyPosesExact(demand, 2, {}, {.timeLimitSeconds = 0.0}); }, "timeLimitSeconds");
    expectThrowWith<std::invalid_argument>(
        [&] { selectKeyPosesExact(demand, 2, {}, {.timeLimitSeconds = std::numeric_limits<double>::quiet_NaN()}); },
        "timeLimitSeconds");
    expectThrowWith<std::invalid_argument>([&] { selectKeyPosesExact(demand, 2, {}, {.maxDemands = 0}); }, "maxDemands");
    expectThrowWith<std::invalid_argument>([&] { selectKeyPosesExact(demand, 2, {}, {.poseCount = 7}); },
                                           "demand 1 names pose 7 but there are only 7 poses");
    const std::vector<KeyPoseDemand> none = {{KeyPoseRows::kNone, 1, 1}};
    expectThrowWith<std::invalid_argument>([&] { selectKeyPosesExact(none, 2); }, "demand 0 names pose 4294967295");
    const std::vector<std::uint32_t> twice = {1, 0, 1};
    expectThrowWith<std::invalid_argument>([&] { selectKeyPosesExact(demand, 2, twice); }, "resident pose 1 is listed twice");
    const std::vector<std::uint32_t> outside = {9};
    expectThrowWith<std::invalid_argument>([&] { selectKeyPosesExact(demand, 2, outside, {.poseCount = 8}); }, "resident entry 0");
    // An infinite time limit is no limit.
    EXPECT_TRUE(selectKeyPosesExact(demand, 2, {}, {.timeLimitSeconds = std::numeric_limits<double>::infinity()}).optimal());
}

// ---------------------------------------------------------------------------------------------
// KeyPoseRows

TEST(KeyPoseRows, KeepsHeldPosesAndFillsEmptyRowsFirst) {
    KeyPoseRows rows(4, 10);
    EXPECT_EQ(rows.hold(std::vector<std::uint32_t>{0, 1}, 1), 2u);
    EXPECT_EQ(rows.hold(std::vector<std::uint32_t>{1, 2}, 2), 1u);  // 1 kept; 2 takes an empty row, 0 stays
    EXPECT_EQ(asSet(rows.held()), (std::set<std::uint32_t>{0, 1, 2}));
    EXPECT_EQ(rows.hold(std::vector<std::uint32_t>{0, 1, 2}, 3), 0u);  // all still there: no update
    for (std::uint32_t p : {0u, 1u, 2u}) EXPECT_EQ(rows.poseIn(rows.rowOf(p)), p);
    EXPECT_EQ(rows.rowOf(5), KeyPoseRows::kNone);
    EXPECT_EQ(rows.rowOf(99), KeyPoseRows::kNone);
    EXPECT_EQ(rows.poseIn(99), KeyPoseRows::kNone);
    rows.clear();
    EXPECT_TRUE(rows.held().empty());
    // An empty row is taken before any held pose, even one last used as long ago as frame 0.
    EXPECT_EQ(rows.hold(std::vector<std::uint32_t>{0}, 0), 1u);
    EXPECT_EQ(rows.hold(std::vector<std::uint32_t>{2}, 1), 1u);
    EXPECT_EQ(asSet(rows.held()), (std::set<std::uint32_t>{0, 2}));
}

TEST(KeyPoseRows, ReplacesTheLeastRecentlyUsedPoseNotWanted) {
    KeyPoseRows rows(3, 10);
    rows.hold(std::vector<std::uint32_t>{0, 1, 2}, 1);
    rows.hold(std::vector<std::uint32_t>{0}, 2);  // 0 used at 2, 1 and 2 at 1
    rows.hold(std::vector<std::uint32_t>{1}, 3);  // 1 used at 3
    const std::uint32_t rowOf2 = rows.rowOf(2);
    EXPECT_EQ(rows.hold(std::vector<std::uint32_t>{5}, 4), 1u);  // 2 is the least recently used
    EXPECT_EQ(rows.rowOf(2), KeyPoseRows::kNone);
    EXPECT_EQ(rows.rowOf(5), rowOf2);
    EXPECT_EQ(rows.hold(std::vector<std::uint32_t>{6}, 5), 1u);  // then 0 (2), before 1 (3) and 5 (4)
    EXPECT_EQ(asSet(rows.held()), (std::set<std::uint32_t>{1, 5, 6}));
    rows.touch(1, 6);                                            // 1 served someone at 6
    EXPECT_EQ(rows.hold(std::vector<std::uint32_t>{7}, 7), 1u);  // so 5 (4) goes
    EXPECT_EQ(asSet(rows.held()), (std::set<std::uint32_t>{1, 6, 7}));
    // A wanted pose is never the victim even when least recently used.
    EXPECT_EQ(rows.hold(std::vector<std::uint32_t>{6, 8}, 8), 1u);  // 6 (5) is wanted: 1 (6) goes
    EXPECT_EQ(asSet(rows.held()), (std::set<std::uint32_t>{6, 7, 8}));
    // Nor when every row was used in this frame: the row not wanted goes.
    rows.touch(7, 9);
    rows.touch(8, 9);
    EXPECT_EQ(rows.hold(std::vector<std::uint32_t>{6, 9}, 9), 1u);  // 6 was used at 8, 7 and 8 at 9: 8 goes (lower row)
    EXPECT_EQ(asSet(rows.held()), (std::set<std::uint32_t>{6, 7, 9}));
}

TEST(KeyPoseRows, RejectsBadPosesNamingThem) {
    EXPECT_THROW(KeyPoseRows(0, 5), std::invalid_argument);
    KeyPoseRows rows(2, 5);
    expectThrowWith<std::invalid_argument>([&] { rows.hold(std::vector<std::uint32_t>{0, 1, 2}, 1); },
                                           "3 poses wanted but the cache has 2 rows");
    expectThrowWith<std::invalid_argument>([&] { rows.hold(std::vector<std::uint32_t>{5}, 1); }, "pose 5 is out of range");
    expectThrowWith<std::invalid_argument>([&] { rows.hold(std::vector<std::uint32_t>{3, 3}, 1); }, "pose 3 is wanted twice");
    EXPECT_TRUE(rows.held().empty());  // a rejected hold changes nothing
}

// ---------------------------------------------------------------------------------------------
// KeyPoseCache

namespace {

// The skinned bar of ActorTestScenes with clips "bend" (2 s: the arm turns to 90 degrees over the
// first second and holds) and "wave" (1 s: -45 degrees and back).
ActorTemplateBuilder barBuilder(const std::string& name, bool withClips = true) {
    ActorTemplateBuilder b = throng::testkit::skinnedBarBuilder(name, std::numeric_limits<double>::infinity());
    if (withClips) {
        b.addClip(throng::testkit::barBendClip());
        ClipChannel wave;
        wave.node = 1;
        wave.times = {0.0f, 0.5f, 1.0f};
        wave.values = {0.0f, -std::numbers::pi_v<float> / 4.0f, 0.0f};
        b.addClip(std::make_shared<AnimationClip>("wave", std::vector<ClipChannel>{wave}));
    }
    return b;
}

KeyPoseCacheSettings settings(KeyPoseMode mode, double rate = 4.0, std::uint32_t rows = 6) {
    KeyPoseCacheSettings s;
    s.rows = rows;
    s.mode = mode;
    s.keyPosesPerSecond = rate;
    return s;
}

}  // namespace

TEST(KeyPoseCache, KeyPosesOfEveryClipAtTheRate) {
    const KeyPoseCache cache(barBuilder("bar").build(), settings(KeyPoseMode::Intermittent));
    ASSERT_EQ(cache.poseCount(), 12u);  // bend: 2 s at 4 per second, wave: 1 s
    EXPECT_EQ(cache.firstPose(0), 0u);
    EXPECT_EQ(cache.posesOf(0), 8u);
    EXPECT_EQ(cache.firstPose(1), 8u);
    EXPECT_EQ(cache.posesOf(1), 4u);
    EXPECT_EQ(cache.clipOf(7), 0);
    EXPECT_EQ(cache.clipOf(8), 1);
    EXPECT_DOUBLE_EQ(cache.timeOf(3), 0.75);
    EXPECT_DOUBLE_EQ(cache.timeOf(9), 0.25);
    EXPECT_EQ(cache.rowCount(), 6u);
    EXPECT_EQ(cache.rows().poseCount(), 12u);
}

TEST(KeyPoseCache, IntermittentSamplesTheNearestKeyPose) {
    const KeyPoseCache cache(barBuilder("bar").build(), settings(KeyPoseMode::Intermittent));
    const auto pose = [&](int clip, double t) {
        const KeyPoseSample s = cache.sample(clip, t);
        EXPECT_EQ(s.a, s.b);
        EXPECT_EQ(s.blend, 0.0f);
        return s.a;
    };
    EXPECT_EQ(pose(0, 0.0), 0u);
    EXPECT_EQ(pose(0, 0.3), 1u);   // 1.2 key-poses in
    EXPECT_EQ(pose(0, 0.4), 2u);   // 1.6
    EXPECT_EQ(pose(0, 2.3), 1u);   // looping
    EXPECT_EQ(pose(0, 1.95), 0u);  // 7.8: nearest is the first again
    EXPECT_EQ(pose(0, -0.3), 7u);  // 1.7 s: 6.8
    EXPECT_EQ(pose(1, 0.6), 10u);  // 2.4 into the second clip
    EXPECT_EQ(pose(0, std::numeric_limits<double>::quiet_NaN()), 0u);
    EXPECT_EQ(pose(1, std::numeric_limits<double>::infinity()), 8u);
    EXPECT_THROW(cache.sample(2, 0.0), std::out_of_range);
    EXPECT_THROW(cache.sample(-1, 0.0), std::out_of_range);
}

TEST(KeyPoseCache, InterpolativeSamplesTheEnclosingPairAndBlend) {
    const KeyPoseCache cache(barBuilder("bar").build(), settings(KeyPoseMode::Interpolative));
    const auto check = [&](int clip, double t, std::uint32_t a, std::uint32_t b, float blend) {
        const KeyPoseSample s = cache.sample(clip, t);
        EXPECT_EQ(s.a, a) << "clip " << clip << " at " << t;
        EXPECT_EQ(s.b, b) << "clip " << clip << " at " << t;
        EXPECT_NEAR(s.blend, blend, 1e-5) << "clip " << clip << " at " << t;
    };
    check(0, 0.0, 0, 1, 0.0f);
    check(0, 0.3, 1, 2, 0.2f);
    check(0, 1.9, 7, 0, 0.6f);    // the last pair wraps to the first key-pose
    check(0, 4.3, 1, 2, 0.2f);    // looping
    check(0, -0.1, 7, 0, 0.6f);
    check(1, 0.6, 10, 11, 0.4f);
    check(1, 0.9, 11, 8, 0.6f);
    check(1, std::numeric_limits<double>::quiet_NaN(), 8, 9, 0.0f);
    // A clip of one key-pose blends it with itself.
    const KeyPoseCache single(barBuilder("bar").build(), settings(KeyPoseMode::Interpolative, 0.1));
    EXPECT_EQ(single.posesOf(1), 1u);
    const KeyPoseSample s = single.sample(1, 0.5);
    EXPECT_EQ(s.a, single.firstPose(1));
    EXPECT_EQ(s.b, s.a);
    EXPECT_EQ(s.blend, 0.0f);
}

TEST(KeyPoseCache, PalettesAreThePosesAtTheirTimes) {
    const auto tmpl = barBuilder("bar").build();
    const KeyPoseCache cache(tmpl, settings(KeyPoseMode::Interpolative));
    std::vector<float> dofs(tmpl->dofValueCount());
    std::vector<Affine> model(tmpl->nodeCount());
    std::vector<glm::mat4> expected(2);
    for (std::uint32_t p = 0; p < cache.poseCount(); ++p) {
        SCOPED_TRACE("pose " + std::to_string(p));
        const int clip = cache.clipOf(p);
        std::copy(tmpl->restDofs().begin(), tmpl->restDofs().end(), dofs.begin());
        tmpl->clips()[static_cast<std::size_t>(clip)]->sample(*tmpl, cache.timeOf(p), true, {}, dofs);
        computeModelTransforms(*tmpl, dofs, {}, model);
        computeSkinPalette(*tmpl, tmpl->skins()[0], model, {}, expected);
        const std::span<const glm::mat4> palette = cache.palette(0, p);
        ASSERT_EQ(palette.size(), 2u);
        for (int j = 0; j < 2; ++j)
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) EXPECT_FLOAT_EQ(palette[j][c][r], expected[j][c][r]);
        // And independently of the pose jobs: the arm's tip (0, 2) turned by the clip's angle.
        const double t = cache.timeOf(p);
        const double angle = clip == 0 ? std::numbers::pi / 2.0 * std::min(t, 1.0)
                                       : -std::numbers::pi / 4.0 * (t <= 0.5 ? t / 0.5 : (1.0 - t) / 0.5);
        const glm::vec4 tip = palette[1] * glm::vec4(0, 2, 0, 1);
        EXPECT_NEAR(tip.x, -std::sin(angle), 1e-5);
        EXPECT_NEAR(tip.y, 1.0 + std::cos(angle), 1e-5);
    }
    EXPECT_TRUE(cache.palette(1, 0).empty());   // no skin 1
    EXPECT_TRUE(cache.palette(0, 12).empty());  // no pose 12
    EXPECT_EQ(cache.paletteBytes(), 12u * 2u * sizeof(glm::mat4));
}

TEST(KeyPoseCache, RejectsTemplatesAndSettingsItCannotCache) {
    const auto tmpl = barBuilder("bar").build();
    expectThrowWith<std::invalid_argument>([] { KeyPoseCache(nullptr, KeyPoseCacheSettings{}); }, "null");
    expectThrowWith<std::invalid_argument>([&] { KeyPoseCache(tmpl, settings(KeyPoseMode::Intermittent, 4.0, 0)); }, "'bar': rows 0");
    expectThrowWith<std::invalid_argument>([&] { KeyPoseCache(tmpl, settings(KeyPoseMode::Intermittent, 4.0, 70000)); }, "rows 70000");
    for (const double rate : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
        expectThrowWith<std::invalid_argument>([&] { KeyPoseCache(tmpl, settings(KeyPoseMode::Intermittent, rate)); }, "keyPosesPerSecond");
    expectThrowWith<std::invalid_argument>([&] { KeyPoseCache(tmpl, settings(static_cast<KeyPoseMode>(7))); }, "unknown mode");
    expectThrowWith<std::invalid_argument>([] { KeyPoseCache(barBuilder("still", false).build(), KeyPoseCacheSettings{}); },
                                           "'still': the template has no clip");
    // A node with rigid geometry of its own cannot come from the cache.
    {
        ActorTemplateBuilder b = barBuilder("rigid-arm");
        SkeletonNode hand;
        hand.name = "hand";
        hand.parent = 1;
        hand.restTranslation = glm::vec3(0, 1, 0);
        hand.geometry.addLevel(100.0, std::make_shared<MeshDrawable>(makeBox("hand", glm::vec3(0), glm::vec3(0.1f))));
        b.addNode(hand);
        expectThrowWith<std::invalid_argument>([&] { KeyPoseCache(b.build(), KeyPoseCacheSettings{}); }, "node 'hand' has rigid geometry");
    }
    // Actor-level geometry that is not skinned.
    {
        ActorTemplateBuilder b("rigid-root");
        SkeletonNode n;
        n.name = "only";
        n.dofs = {Dof::rotation(glm::vec3(0, 0, 1), -1.0f, 1.0f)};
        b.addNode(n);
        b.rootGeometry().addLevel(100.0, std::make_shared<MeshDrawable>(makeBox("box", glm::vec3(0), glm::vec3(1))));
        ClipChannel c;
        c.node = 0;
        c.times = {0.0f, 1.0f};
        c.values = {0.0f, 0.5f};
        b.addClip(std::make_shared<AnimationClip>("turn", std::vector<ClipChannel>{c}));
        expectThrowWith<std::invalid_argument>([&] { KeyPoseCache(b.build(), KeyPoseCacheSettings{}); }, "no skinned actor-level mesh");
    }
}

// Demands of several processes add up per pair of poses, in increasing order of first pose: the
// list one process holding every actor would have made.
TEST(KeyPoseDemands, DemandsOfSeveralProcessesAddUpInOrder) {
    std::vector<KeyPoseDemand> combined;
    addKeyPoseDemands(combined, std::vector<KeyPoseDemand>{{2, 3, 1}, {5, 6, 2}});
    addKeyPoseDemands(combined, std::vector<KeyPoseDemand>{{0, 1, 4}, {2, 3, 2}, {9, 9, 1}});
    addKeyPoseDemands(combined, std::vector<KeyPoseDemand>{});
    addKeyPoseDemands(combined, std::vector<KeyPoseDemand>{{5, 6, 1}, {7, 8, 3}});
    const std::vector<std::array<std::uint32_t, 3>> expected{{0, 1, 4}, {2, 3, 3}, {5, 6, 3}, {7, 8, 3}, {9, 9, 1}};
    ASSERT_EQ(combined.size(), expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
        EXPECT_EQ(combined[k].a, expected[k][0]);
        EXPECT_EQ(combined[k].b, expected[k][1]);
        EXPECT_EQ(combined[k].actors, expected[k][2]);
    }
}

// Rows copied from another process's answer every lookup as those do; a copy that cannot be rows
// of this cache is refused and changes nothing.
TEST(KeyPoseRows, CopiedRowsAnswerAsTheOriginalAndBadCopiesChangeNothing) {
    KeyPoseRows original(4, 20), copy(4, 20);
    original.hold(std::vector<std::uint32_t>{7, 3, 12}, 1);
    original.hold(std::vector<std::uint32_t>{3, 19}, 2);
    copy.copyRows(original.rowPoses());
    for (std::uint32_t p = 0; p < 20; ++p) EXPECT_EQ(copy.rowOf(p), original.rowOf(p)) << "pose " << p;
    EXPECT_EQ(copy.heldCount(), original.heldCount());
    const std::vector<std::uint32_t> before(copy.rowPoses().begin(), copy.rowPoses().end());
    const std::uint32_t none = KeyPoseRows::kNone;
    EXPECT_THROW(copy.copyRows(std::vector<std::uint32_t>{1, 2, 3}), std::invalid_argument);
    EXPECT_THROW(copy.copyRows(std::vector<std::uint32_t>{1, 20, none, none}), std::invalid_argument);
    try {
        copy.copyRows(std::vector<std::uint32_t>{5, none, 6, 5});
        FAIL() << "a pose in two rows was copied";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("row 3 holds pose 5, which an earlier row holds"), std::string::npos) << e.what();
    }
    EXPECT_EQ(std::vector<std::uint32_t>(copy.rowPoses().begin(), copy.rowPoses().end()), before);
    copy.copyRows(std::vector<std::uint32_t>{5, none, 6, 1});  // the refused copies left nothing behind
    EXPECT_EQ(copy.rowOf(5), 0u);
    EXPECT_EQ(copy.rowOf(1), 3u);
    EXPECT_EQ(copy.rowOf(7), none);
}
