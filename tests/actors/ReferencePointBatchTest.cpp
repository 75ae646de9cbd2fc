// Phase 1 in batches: sines and cosines two at a time (detail::sinCos), paths many at a time
// (RefpointPath::atEach), behaviours asked for runs of actors (Behaviour::referencePoints). Every
// batched result must carry the bits of the single call, whatever the batch around it, so that
// threads, chunking and the two processing methods cannot tell them apart.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "throng/testkit/ActorTestScenes.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/ProceduralGait.h"
#include "throng/actors/RefpointPath.h"
#include "throng/scenegraph/Camera.h"
#include "throng/actors/detail/SinCos.h"

using namespace throng;
using namespace throng::testkit;

namespace {

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool sameBits(const Mat4& a, const Mat4& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Angles a walker can meet: small, around multiples of pi/2, negative, and large (long runs).
std::vector<double> testAngles(std::size_t n) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> a = {0.0, -0.0, 1e-300, 1.5707963267948966, 3.141592653589793, -2.5, 1e5, 123456.789, 1e9};
    while (a.size() < n) a.push_back(std::ldexp(u(rng), int(std::floor(40.0 * (u(rng) + 1.0) / 2.0)) - 10));
    a.resize(n);
    return a;
}

}  // namespace

TEST(SinCos, EveryAngleGetsTheBitsOfItsOwnCallWhateverBatchHoldsIt) {
    const std::vector<double> angles = testAngles(41);
    std::vector<double> singleSin(angles.size()), singleCos(angles.size());
    for (std::size_t k = 0; k < angles.size(); ++k) detail::sinCos(angles[k], singleSin[k], singleCos[k]);
    // Batches starting at every offset, of every length: odd ones end with a lane alone.
    for (std::size_t first = 0; first < angles.size(); ++first)
        for (std::size_t n = 0; first + n <= angles.size(); n += 1 + n / 4) {
            std::vector<double> s(n, 9.0), c(n, 9.0);
            detail::sinCos(angles.data() + first, s.data(), c.data(), n);
            for (std::size_t k = 0; k < n; ++k) {
                ASSERT_TRUE(sameBits(s[k], singleSin[first + k])) << "sine of angle " << first + k << " in a batch of " << n;
                ASSERT_TRUE(sameBits(c[k], singleCos[first + k])) << "cosine of angle " << first + k << " in a batch of " << n;
            }
        }
}

TEST(SinCos, StaysWithinFourUlpOfTheStandardLibrary) {
    for (double a : testAngles(2000)) {
        double s, c;
        detail::sinCos(a, s, c);
        const double es = std::sin(a), ec = std::cos(a);
        // Four ulp of the value, or of the smallest normal double for values near zero.
        const auto ulps = [](double x) { return 4.0 * std::max(std::abs(x), 1e-300) * std::numeric_limits<double>::epsilon(); };
        EXPECT_LE(std::abs(s - es), ulps(es) + 1e-300) << "sin(" << a << ")" << (detail::sinCosVectorised() ? " (libmvec)" : "");
        EXPECT_LE(std::abs(c - ec), ulps(ec) + 1e-300) << "cos(" << a << ")";
    }
}

TEST(SinCos, NonFiniteAnglesGiveNaNAndLeaveTheirNeighboursAlone) {
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    const double angles[4] = {0.5, nan, inf, -inf};
    double s[4], c[4];
    detail::sinCos(angles, s, c, 4);
    for (int k = 1; k < 4; ++k) {
        EXPECT_TRUE(std::isnan(s[k])) << k;
        EXPECT_TRUE(std::isnan(c[k])) << k;
    }
    double s0, c0;
    detail::sinCos(0.5, s0, c0);
    EXPECT_TRUE(sameBits(s[0], s0));
    EXPECT_TRUE(sameBits(c[0], c0));
}

TEST(RefpointPath, AtEachGivesEveryPathTheMatrixAndTallyOfItsOwnCall) {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<RefpointPath> paths;
    for (int k = 0; k < 40; ++k)  // standing and walking mixed, across the 16-path blocks
        paths.push_back(RefpointPath{Vec3(50 * u(rng), u(rng), 50 * u(rng)), 7 * u(rng), k % 3 ? 0.5 + 10 * std::abs(u(rng)) : 0.0,
                                     1.2 + 0.3 * u(rng)});
    for (double time : {0.0, 1.7, 1e5})
        for (std::size_t n : {0u, 1u, 2u, 15u, 16u, 17u, 33u, 40u}) {
            std::vector<Mat4> out(n + 1, Mat4(7.0));
            OpTally batched;
            RefpointPath::atEach({paths.data(), n}, time, {out.data(), n}, &batched);
            OpTally single;
            for (std::size_t k = 0; k < n; ++k)
                ASSERT_TRUE(sameBits(out[k], paths[k].at(time, &single))) << "path " << k << " of " << n << " at " << time;
            EXPECT_TRUE(sameBits(out[n], Mat4(7.0))) << "wrote past the paths";
            EXPECT_EQ(batched.fmult(), single.fmult()) << n << " paths";
        }
}

TEST(RefpointPath, AtEachRejectsAnOutputShorterThanItsPaths) {
    const std::vector<RefpointPath> paths(3);
    std::vector<Mat4> out(2);
    try {
        RefpointPath::atEach(paths, 0.0, out);
        FAIL() << "no exception";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("'out' holds 2"), std::string::npos) << e.what();
    }
}

namespace {
// A KeyframeBehaviour that batches nothing: Behaviour's default referencePoints.
class UnbatchedKeyframes : public KeyframeBehaviour {
public:
    using KeyframeBehaviour::KeyframeBehaviour;
    void referencePoints(std::span<const std::uint32_t> slots, const FrameContext& context, OpTally* ops,
                         std::span<Mat4> out) override {
        Behaviour::referencePoints(slots, context, ops, out);
    }
};
}  // namespace

TEST(Behaviour, BatchedReferencePointsEqualSingleCallsForEveryBehaviour) {
    const auto humanoid = makeSeedHumanoid();
    KeyframeBehaviour keyframes;
    UnbatchedKeyframes unbatched;
    ProceduralGait gait;
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<std::uint32_t> slots;
    for (int k = 0; k < 37; ++k) {
        KeyframeBehaviour::Actor a;
        a.tmpl = humanoid;
        a.position = Vec3(100 * u(rng), 0, 100 * u(rng));
        a.heading = 6.3 * u(rng);
        a.pathRadius = k % 4 ? 3 + 10 * u(rng) : 0.0;
        a.pathSpeed = 1.3;
        slots.push_back(keyframes.addActor(a));
        unbatched.addActor(a);
        ProceduralGait::Actor g;
        g.center = a.position;
        g.radius = a.pathRadius;
        g.phase = a.heading;
        gait.addActor(g);
    }
    std::reverse(slots.begin(), slots.end());  // slots in any order
    for (Behaviour* b : std::initializer_list<Behaviour*>{&keyframes, &unbatched, &gait}) {
        const FrameContext context{12.25, 1.0 / 30.0, 3, nullptr};
        std::vector<Mat4> out(slots.size());
        OpTally batched, single;
        b->referencePoints(slots, context, &batched, out);
        for (std::size_t k = 0; k < slots.size(); ++k)
            ASSERT_TRUE(sameBits(out[k], b->referencePoint(slots[k], context, &single))) << "slot " << slots[k];
        EXPECT_EQ(batched.fmult(), single.fmult());
    }
}

// The run-forming loop of phase 1 sees interleaved behaviours and groups whose ids are not
// consecutive (the random crowd has both): every actor's Reference Point is still its own call's.
TEST(Behaviour, BothProcessingMethodsStoreEachActorsOwnReferencePoint) {
    for (Processing processing : {Processing::Actor, Processing::Traditional}) {
        auto world = makeRandomCrowd(9, 700, 60.0);
        ActorProcessor processor(world->crowd);
        processor.setThreads(2);
        processor.setProcessing(processing);
        Camera camera;
        camera.setPerspective(1.1, 1.6, 0.1, 300.0);
        camera.setLookAt(Vec3(40, 10, 40), Vec3(0.0), Vec3(0, 1, 0));
        processor.processFrame(*world->root, camera, 2.5);
        const Crowd::State& s = world->crowd.state();
        const FrameContext context{2.5, 0.0, 0, nullptr};
        std::size_t checked = 0;
        for (ActorId id : world->ids) {
            if (!s.owner[id]) continue;
            ASSERT_TRUE(sameBits(s.refLocal[id], s.behaviour[id]->referencePoint(s.slot[id], context, nullptr)))
                << "actor " << id << (processing == Processing::Actor ? " (actor processing)" : " (traditional)");
            ++checked;
        }
        EXPECT_EQ(checked, world->ids.size());
    }
}
