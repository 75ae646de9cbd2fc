// bench_keypose_timeline's parts (benchmarks/actors/KeyPoseTimeline.h, seed 004 Figure 12): the
// schedule offers all clips, then one, then one more each phase, with frames landing on a boundary
// in the new phase; the re-pick rule moves every actor off a clip no longer offered, spreads the
// crowd over the offered clips, keeps the others when told to, and draws the same on every run;
// the behaviour plays the clip an actor chose and follows a new choice; the phase summary averages
// what it is given.

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "KeyPoseTimeline.h"
#include "throng/actors/ActorTemplate.h"
#include "throng/actors/SeedHumanoid.h"

using namespace throng;
using namespace throng::bench;

TEST(KeyPoseTimeline, TheScheduleOffersAllClipsThenOneThenOneMoreEachPhase) {
    const ClipSchedule s{5, 5.0};
    EXPECT_EQ(s.phases(), 6u);
    EXPECT_DOUBLE_EQ(s.duration(), 30.0);
    const std::vector<std::uint32_t> expected{5, 1, 2, 3, 4, 5};
    for (std::uint32_t k = 0; k < s.phases(); ++k) EXPECT_EQ(s.available(k), expected[k]) << "phase " << k;
    EXPECT_EQ(s.phaseAt(0.0), 0u);
    EXPECT_EQ(s.phaseAt(4.999), 0u);
    EXPECT_EQ(s.phaseAt(5.0), 1u);
    EXPECT_EQ(s.phaseAt(24.99), 4u);
    EXPECT_EQ(s.phaseAt(25.0), 5u);
    EXPECT_EQ(s.phaseAt(29.97), 5u);
    EXPECT_EQ(s.phaseAt(1000.0), 5u) << "beyond the schedule: its last phase";
    EXPECT_EQ(s.phaseAt(-1.0), 0u);
    EXPECT_EQ(s.phaseAt(std::nan("")), 0u);
    // Every frame of every common rate that lands on a boundary is in the new phase.
    for (int fps : {24, 25, 30, 60, 90, 144})
        for (int k = 1; k <= 5; ++k) EXPECT_EQ(s.phaseAt(double(k * 5 * fps) / fps), std::uint32_t(k)) << fps << " fps, boundary " << k;
    // Other phase lengths: 0.3 s phases, frame 9 of 30 fps is at 0.3 s.
    EXPECT_EQ((ClipSchedule{3, 0.3}.phaseAt(9.0 / 30.0)), 1u);
}

TEST(KeyPoseTimeline, ActorsOnAClipNoLongerOfferedAlwaysChooseAgainAndTheRestWhenTold) {
    const std::vector<double> durations{1.5, 3.3, 0.7, 1.0, 2.0};
    UnitRandom random(7);
    std::vector<ClipChoice> choices(5000);
    EXPECT_EQ(chooseClips(choices, 5, durations, 1.0, random), choices.size()) << "share 1: everyone chooses";
    std::vector<int> count(5, 0);
    for (const ClipChoice& c : choices) {
        ASSERT_LT(c.clip, 5u);
        EXPECT_GE(c.offset, 0.0);
        EXPECT_LT(c.offset, durations[c.clip]);
        ++count[c.clip];
    }
    for (int n : count) EXPECT_NEAR(n, 1000, 150) << "a uniform choice among the five";

    // Down to one clip, nobody else choosing: exactly those not on clip 0 choose, and land on it.
    std::vector<ClipChoice> before = choices;
    const std::size_t moved = chooseClips(choices, 1, durations, 0.0, random);
    EXPECT_EQ(moved, choices.size() - std::size_t(count[0]));
    for (std::size_t i = 0; i < choices.size(); ++i) {
        EXPECT_EQ(choices[i].clip, 0u);
        if (before[i].clip == 0) {
            EXPECT_EQ(choices[i].offset, before[i].offset) << "an actor whose clip stays keeps its time";
        }
    }
    // Two clips, share 0: nobody takes up the new one (why the benchmark's default is 1).
    before = choices;
    EXPECT_EQ(chooseClips(choices, 2, durations, 0.0, random), 0u);
    for (std::size_t i = 0; i < choices.size(); ++i) EXPECT_EQ(choices[i].offset, before[i].offset);
    // Two clips, share 1: both in use, about half each.
    EXPECT_EQ(chooseClips(choices, 2, durations, 1.0, random), choices.size());
    std::size_t onNew = 0;
    for (const ClipChoice& c : choices) onNew += c.clip == 1;
    EXPECT_NEAR(double(onNew), 2500.0, 200.0);
    // A share between: about that share of the actors choose.
    const std::size_t some = chooseClips(choices, 3, durations, 0.25, random);
    EXPECT_NEAR(double(some), 1250.0, 150.0);
}

TEST(KeyPoseTimeline, TheSameSeedGivesTheSameChoices) {
    const std::vector<double> durations{1.0, 2.0, 3.0};
    std::vector<ClipChoice> a(300), b(300);
    UnitRandom ra(42), rb(42);
    chooseClips(a, 3, durations, 1.0, ra);
    chooseClips(b, 3, durations, 1.0, rb);
    chooseClips(a, 1, durations, 0.5, ra);
    chooseClips(b, 1, durations, 0.5, rb);
    for (std::size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].clip, b[i].clip);
        EXPECT_EQ(a[i].offset, b[i].offset);
    }
    // The stream itself is fixed (std::mt19937_64 is specified; the conversion is ours).
    UnitRandom r(1);
    EXPECT_DOUBLE_EQ(r.next(), double(std::mt19937_64(1)() >> 11) * 0x1.0p-53);
}

TEST(KeyPoseTimeline, BadArgumentsAreRefused) {
    std::vector<ClipChoice> c(3);
    UnitRandom random(1);
    const std::vector<double> durations{1.0, 2.0};
    EXPECT_THROW(chooseClips(c, 0, durations, 1.0, random), std::invalid_argument);
    EXPECT_THROW(chooseClips(c, 3, durations, 1.0, random), std::invalid_argument);
    EXPECT_THROW(chooseClips(c, 2, durations, 1.5, random), std::invalid_argument);
    EXPECT_THROW(chooseClips(c, 2, durations, std::nan(""), random), std::invalid_argument);
    EXPECT_THROW(chooseClips(c, 2, std::vector<double>{1.0, 0.0}, 1.0, random), std::invalid_argument);
    const auto humanoid = makeSeedHumanoid();
    EXPECT_THROW(ClipChoiceBehaviour(nullptr, {0}), std::invalid_argument);
    EXPECT_THROW(ClipChoiceBehaviour(humanoid, {}), std::invalid_argument);
    EXPECT_THROW(ClipChoiceBehaviour(humanoid, {int(humanoid->clips().size())}), std::invalid_argument);
    ClipChoiceBehaviour b(humanoid, {0});
    EXPECT_THROW(b.addActor(Vec3(0), 0.0, ClipChoice{1, 0.0}), std::invalid_argument);
    EXPECT_THROW(b.addActor(Vec3(0, std::nan(""), 0), 0.0, ClipChoice{}), std::invalid_argument);
    EXPECT_THROW(b.setChoice(0, ClipChoice{}), std::invalid_argument) << "no actor yet";
}

TEST(KeyPoseTimeline, TheBehaviourPlaysTheChosenClipAndFollowsANewChoice) {
    const auto humanoid = makeSeedHumanoid();
    ASSERT_GE(humanoid->clips().size(), 1u);
    const int last = int(humanoid->clips().size()) - 1;
    ClipChoiceBehaviour b(humanoid, {last, 0});
    const std::uint32_t slot = b.addActor(Vec3(1, 0, 2), 0.5, ClipChoice{0, 0.25});
    EXPECT_EQ(b.mainClip(slot), last) << "schedule clip 0 is the template's clip `last`";
    EXPECT_DOUBLE_EQ(b.clipTime(slot, 2.0), 2.25);
    b.setChoice(slot, ClipChoice{1, 0.5});
    EXPECT_EQ(b.mainClip(slot), 0);
    EXPECT_DOUBLE_EQ(b.clipTime(slot, 2.0), 2.5);
    const Mat4 ref = b.referencePoint(slot, FrameContext{3.0, 0.0, 0, nullptr}, nullptr);
    EXPECT_DOUBLE_EQ(ref[3].x, 1.0);
    EXPECT_DOUBLE_EQ(ref[3].z, 2.0);
    EXPECT_TRUE(b.skeletonRootExtent(slot).valid());
    EXPECT_TRUE(std::isinf(b.levelEnds().front())) << "one level: full detail everywhere";
}

TEST(KeyPoseTimeline, ThePhaseSummaryAveragesEachPhase) {
    std::vector<TimelineFrame> frames;
    // Phase 0: three frames, 10 actors, served 10, 8, 6; updates 50, 2, 4.
    frames.push_back({0, 0.0, 0, 5, 10, 10, 0, 50, 40, 50});
    frames.push_back({1, 0.1, 0, 5, 10, 8, 2, 2, 41, 50});
    frames.push_back({2, 0.2, 0, 5, 10, 6, 4, 4, 42, 50});
    // Phase 1: one frame with an empty band.
    frames.push_back({3, 0.3, 1, 1, 0, 0, 0, 7, 0, 50});
    const auto phases = summarizeTimeline(frames);
    ASSERT_EQ(phases.size(), 2u);
    const TimelinePhase& p = phases[0];
    EXPECT_EQ(p.frames, 3u);
    EXPECT_EQ(p.available, 5u);
    EXPECT_DOUBLE_EQ(p.start, 0.0);
    EXPECT_DOUBLE_EQ(p.end, 0.2);
    EXPECT_DOUBLE_EQ(p.servedShare, 0.8);
    EXPECT_DOUBLE_EQ(p.minServedShare, 0.6);
    EXPECT_NEAR(p.servedSd, std::sqrt(8.0 / 3.0), 1e-12) << "10, 8, 6 about 8";
    EXPECT_DOUBLE_EQ(p.misses, 2.0);
    EXPECT_DOUBLE_EQ(p.updates, 56.0 / 3.0);
    EXPECT_EQ(p.firstUpdates, 50u);
    EXPECT_DOUBLE_EQ(p.laterUpdates, 3.0);
    EXPECT_DOUBLE_EQ(p.laterUpdatesSd, 1.0);
    EXPECT_DOUBLE_EQ(p.wanted, 41.0);
    EXPECT_EQ(phases[1].frames, 1u);
    EXPECT_DOUBLE_EQ(phases[1].servedShare, 1.0) << "an empty band counts as all served";
    EXPECT_DOUBLE_EQ(phases[1].laterUpdates, 0.0);
    std::ostringstream csv;
    writeTimelineCsvHeader(csv);
    writeTimelineCsv(csv, "intermittent", std::span(frames).first(1));
    EXPECT_EQ(csv.str(), "mode,frame,time,phase,clips_available,band,served,misses,updates,wanted,held\n"
                         "intermittent,0,0.0000,0,5,10,10,0,50,40,50\n");
}
