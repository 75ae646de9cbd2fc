// Flock, gaze and idle groups: birds stay over their area and band; gazing people turn neck and
// head towards someone within limits, only as near as their bands allow; and everything is
// deterministic and counted as the effect it is.

#include <gtest/gtest.h>

#include <cstring>
#include <numbers>

#include "throng/testkit/Cameras.h"
#include "throng/actors/Actor.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/ProceduralBird.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Group.h"
#include "throng/sim/CounterRng.h"
#include "throng/sim/Flock.h"
#include "throng/sim/GazeLayer.h"
#include "throng/sim/IdleGroups.h"
#include "throng/sim/SimulationClock.h"

using namespace throng;
using namespace throng::sim;

namespace {

Camera overview() {
    return testkit::lookingAt(Vec3(0, 60, 120), Vec3(0.0), {.fovY = 1.2});
}

struct Birds {
    EffectCounters counters;
    Crowd crowd;
    std::shared_ptr<Group> root = std::make_shared<Group>();
    std::shared_ptr<Flock> flock;
};

std::unique_ptr<Birds> birds(int n) {
    auto b = std::make_unique<Birds>();
    Flock::Settings s;
    s.size = glm::dvec2(120.0);
    b->flock = std::make_shared<Flock>(s, std::vector<double>{60.0, 1e9}, &b->counters);
    static const auto bird = makeProceduralBird();
    for (int i = 0; i < n; ++i)
        b->root->addChild(b->crowd.makeActorNode(
            b->crowd.add(bird, b->flock, b->flock->addBird({bird, 0, std::uint64_t(i)}))));
    return b;
}

}  // namespace

TEST(Flock, BirdsStayOverTheirAreaAndBandAndAreDeterministic) {
    auto one = birds(150), two = birds(150);
    ActorProcessor p1(one->crowd), p2(two->crowd);
    p2.setThreads(2);
    SimulationClock clock;
    for (int f = 0; f < 1200; ++f, clock.advance()) {
        one->crowd.step(clock.context());
        p1.processFrame(*one->root, overview(), clock.time());
        two->crowd.step(clock.context());
        p2.processFrame(*two->root, overview(), clock.time());
    }
    for (std::uint32_t i = 0; i < 150; ++i) {
        const glm::dvec3 p = one->flock->position(i);
        EXPECT_LT(std::abs(p.x), 60.0 + 25.0) << i;
        EXPECT_LT(std::abs(p.z), 60.0 + 25.0) << i;
        EXPECT_GT(p.y, 25.0 - 10.0) << i;
        EXPECT_LT(p.y, 40.0 + 10.0) << i;
        EXPECT_EQ(p, two->flock->position(i)) << "threads change nothing";
    }
    EXPECT_EQ(one->counters.of("flight").constructed, 1u);
    EXPECT_EQ(one->counters.of("flight").ticks, 150u * 1199u);
    EXPECT_THROW(one->flock->addBird({makeProceduralBird(), 0, 999}), std::invalid_argument) << "after the start";
}

namespace {

// Four seed humanoids standing in a square, facing its centre, posed by `behaviour`.
struct Group4 {
    EffectCounters counters;
    Crowd crowd;
    std::shared_ptr<Group> root = std::make_shared<Group>();
    std::shared_ptr<IdleGroups> idle;
    std::shared_ptr<GazeLayer> gaze;
    std::vector<ActorId> ids;
};

std::unique_ptr<Group4> standingGroup(bool gaze, Vec3 where = Vec3(0.0)) {
    auto g = std::make_unique<Group4>();
    static const auto humanoid = makeSeedHumanoid();
    g->idle = std::make_shared<IdleGroups>(std::vector<double>{60.0, 1e9}, &g->counters);
    if (gaze) {
        GazeLayer::Settings s;
        s.levels = {15.0, 40.0};
        g->gaze = std::make_shared<GazeLayer>(g->idle, s, &g->counters);
    }
    for (int k = 0; k < 4; ++k) {
        const double a = k * std::numbers::pi / 2.0;
        KeyframeBehaviour::Actor a0;
        a0.tmpl = humanoid;
        a0.clip = humanoid->findClip("walk");
        a0.timeScale = 0.0;  // a held pose: standing
        a0.position = where + Vec3(1.2 * std::sin(a), 0.0, 1.2 * std::cos(a));
        a0.heading = a + std::numbers::pi;  // facing the centre
        std::uint32_t slot = g->idle->addPerson(a0);
        std::shared_ptr<Behaviour> b = g->idle;
        if (gaze) {
            slot = g->gaze->wrap(slot, humanoid, std::uint64_t(k));
            b = g->gaze;
        }
        g->ids.push_back(g->crowd.add(humanoid, b, slot));
        g->root->addChild(g->crowd.makeActorNode(g->ids.back()));
    }
    return g;
}

Camera at(double distance) { return testkit::lookingAt(Vec3(0, 1.6, distance), Vec3(0, 1.2, 0), {.fovY = 0.9}); }

}  // namespace

TEST(Gaze, PeopleTurnTowardsSomeoneWithinLimitsAndOnlyAsNearAsTheBandsAllow) {
    auto plain = standingGroup(false), looking = standingGroup(true);
    ActorProcessor pp(plain->crowd), pl(looking->crowd);
    const auto humanoid = makeSeedHumanoid();
    const int neck = humanoid->findNode("neck");
    std::size_t turned = 0;
    SimulationClock clock;
    for (int f = 0; f < 300; ++f, clock.advance()) {
        plain->crowd.step(clock.context());
        pp.processFrame(*plain->root, at(8.0), clock.time());
        looking->crowd.step(clock.context());
        pl.processFrame(*looking->root, at(8.0), clock.time());
        if (f < 10) continue;
        for (std::uint32_t k = 0; k < 4; ++k) {
            const int target = looking->gaze->lookingAt(k);
            ASSERT_GE(target, 0) << "the others stand within range";
            ASSERT_NE(target, int(k));
            const auto a = plain->crowd.dofs(plain->ids[k]), b = looking->crowd.dofs(looking->ids[k]);
            const std::uint32_t yaw = humanoid->dofValueOffset(std::size_t(neck), 1);  // the neck's vertical axis
            EXPECT_LE(std::abs(b[yaw]), 1.2f + 1e-6f) << "within the joint limit";
            turned += std::abs(b[yaw] - a[yaw]) > 0.05f;
        }
    }
    EXPECT_GT(turned, 500u) << "heads turn";
    EXPECT_EQ(looking->counters.of("gaze").constructed, 1u);
    EXPECT_EQ(looking->counters.of("gaze").ticks, 4u * 300u);
    EXPECT_EQ(plain->counters.of("gaze").constructed, 0u) << "not declared, never made";
    EXPECT_EQ(plain->counters.of("gaze").ticks, 0u);
    EXPECT_EQ(looking->counters.of("idle").ticks, 4u * 300u);
    // Beyond the gaze's last band (40 m), nothing turns: every node posed this frame has the
    // base's values (deactivated nodes keep whatever they last had, and are not drawn).
    plain->crowd.step(clock.context());
    pp.processFrame(*plain->root, at(50.0), clock.time());
    looking->crowd.step(clock.context());
    pl.processFrame(*looking->root, at(50.0), clock.time());
    for (std::uint32_t k = 0; k < 4; ++k) {
        const ActorId id = looking->ids[k];
        std::vector<std::uint8_t> active(humanoid->nodeCount());
        computeActiveNodes(*humanoid, detailDistanceSquared(looking->crowd.skeletonRoot(id), at(50.0).eye(), 1.0, 1.0f), active);
        EXPECT_EQ(active[std::size_t(neck)], 0) << "the neck is off at 50 m";
        const auto a = plain->crowd.dofs(plain->ids[k]), b = looking->crowd.dofs(id);
        for (std::size_t i = 0; i < humanoid->nodeCount(); ++i) {
            if (!active[i]) continue;
            const std::uint32_t end = i + 1 < humanoid->nodeCount() ? humanoid->dofOffset(i + 1) : humanoid->dofValueCount();
            for (std::uint32_t v = humanoid->dofOffset(i); v < end; ++v)
                EXPECT_EQ(a[v], b[v]) << "actor " << k << " node " << humanoid->nodes()[i].name;
        }
    }
}

TEST(Gaze, TheSklsrootBsphereGrowsToHoldATurnedHead) {
    auto plain = standingGroup(false), looking = standingGroup(true);
    EXPECT_GT(looking->crowd.skeletonRootRadius(0), plain->crowd.skeletonRootRadius(0));
    // The head stays inside the grown sphere whatever it looks at.
    ActorProcessor p(looking->crowd);
    SimulationClock clock;
    for (int f = 0; f < 400; ++f, clock.advance()) {
        looking->crowd.step(clock.context());
        p.processFrame(*looking->root, at(6.0), clock.time());
        for (ActorId id : looking->ids) {
            const ActorTemplate& t = looking->crowd.templateOf(id);
            std::vector<Affine> model(t.nodeCount());
            std::vector<BoundingSphere> g(t.nodeCount()), sub(t.nodeCount());
            computeModelTransforms(t, looking->crowd.dofs(id), {}, model);
            computeInternalSpheres(t, model, {}, g, sub);
            for (const BoundingSphere& s : g)
                if (s.valid()) {
                    ASSERT_LE(glm::length(s.center()) + s.radius(), looking->crowd.skeletonRootRadius(id));
                }
        }
    }
}

namespace {

// People drifting over a square: each frame every one moves a little, from its own stream. Actors
// the test marks absent are "simulated elsewhere": their state here is stale (far off).
class Drifters : public Behaviour {
public:
    explicit Drifters(std::size_t n) : at_(n), present_(n, 1) {
        for (std::size_t i = 0; i < n; ++i) at_[i] = glm::dvec3(CounterRng(7, i).uniform(0, 0.0, 60.0), 0.0, CounterRng(7, i).uniform(1, 0.0, 60.0));
    }
    void advance(const FrameContext& context) override {
        ++frame_;
        for (std::size_t i = 0; i < at_.size(); ++i) {
            const CounterRng rng(8, i);
            at_[i] += glm::dvec3(rng.uniform(2 * frame_, -0.05, 0.05), 0.0, rng.uniform(2 * frame_ + 1, -0.05, 0.05));
        }
        (void)context;
    }
    std::span<const double> levelEnds() const override { return ends_; }
    Mat4 referencePoint(std::uint32_t slot, const FrameContext&, OpTally*) override {
        Mat4 m(1.0);
        m[3] = Vec4(present_[slot] ? at_[slot] : glm::dvec3(1e6 + slot, 0.0, 0.0), 1.0);
        return m;
    }
    RootPose skeletonRoot(std::uint32_t, double, int, OpTally*) override { return RootPose{}; }
    void pose(std::uint32_t, double, int, const ActorTemplate&, std::span<const std::uint8_t>, std::span<float>, OpTally*) override {}
    BoundingSphere skeletonRootExtent(std::uint32_t) const override { return BoundingSphere(Vec3(0.0), 1.0); }
    bool posesFromTemplateClips() const override { return true; }
    bool presence(std::span<const std::uint32_t> slots, std::span<std::uint8_t> present) const override {
        for (std::size_t k = 0; k < slots.size(); ++k) present[k] = present_[slots[k]];
        return false;
    }
    std::size_t bytesPerSlot() const override { return sizeof(glm::dvec3); }

    glm::dvec3 at(std::size_t slot) const { return at_[slot]; }
    std::vector<std::uint8_t>& presentFlags() { return present_; }

private:
    std::vector<double> ends_{100.0};
    std::vector<glm::dvec3> at_;
    std::vector<std::uint8_t> present_;
    std::uint64_t frame_ = 0;
};

}  // namespace

// Whom someone looks at depends only on who is within range now: a process holding only the
// actors near some place (the others absent, their state stale) chooses for everyone there as a
// process holding all of them does. A choice holds through its period while the same people stay
// near, and changes from one period to the next.
TEST(Gaze, TheChoiceDependsOnlyOnWhoIsNear) {
    const std::size_t n = 300;
    const auto humanoid = makeSeedHumanoid();
    auto all = std::make_shared<Drifters>(n), part = std::make_shared<Drifters>(n);
    GazeLayer::Settings settings;
    settings.range = 6.0;
    GazeLayer whole(all, settings), near(part, settings);
    for (std::uint32_t i = 0; i < n; ++i) whole.wrap(i, humanoid, i), near.wrap(i, humanoid, i);
    SimulationClock clock;
    std::size_t compared = 0, looking = 0, changes = 0, held = 0;
    std::vector<int> last(n, -2);
    for (int f = 0; f < 400; ++f, clock.advance()) {
        // The part holds those within 20 m of the square's centre, and everyone within 6 m of them.
        for (std::size_t i = 0; i < n; ++i)
            part->presentFlags()[i] = glm::length(glm::dvec2(all->at(i).x - 30.0, all->at(i).z - 30.0)) < 26.5;
        whole.advance(clock.context());
        near.advance(clock.context());
        for (std::uint32_t i = 0; i < n; ++i) {
            const int target = whole.lookingAt(i);
            if (target >= 0) {
                ++looking;
                const glm::dvec3 d = all->at(std::size_t(target)) - all->at(i);
                ASSERT_LE(d.x * d.x + d.z * d.z, 36.0 + 1e-9) << "actor " << i << " looks at someone out of range";
            }
            if (last[i] != -2) (target == last[i] ? held : changes) += 1;
            last[i] = target;
            if (glm::length(glm::dvec2(all->at(i).x - 30.0, all->at(i).z - 30.0)) >= 20.0) continue;
            ASSERT_EQ(near.lookingAt(i), target) << "frame " << f << ", actor " << i << ": the part chose otherwise";
            ++compared;
        }
    }
    EXPECT_GT(compared, 400u * 80u) << "enough actors near the centre";
    EXPECT_GT(looking, 400u * n / 2) << "most people have someone within 6 m";
    EXPECT_GT(changes, 400u) << "choices change from period to period";
    EXPECT_GT(held, 20u * changes) << "and hold within a period (2.5-5 s)";
}

// An actor's DOF values persist from frame to frame, and a clip that does not key the neck leaves it
// as it was: the turn of the frame before must not carry over (RobotExpressive's Idle keys no
// neck). Posing the same actor at the same time twice, on the values it kept, gives the same pose.
TEST(Gaze, ATurnDoesNotCarryOverWhenTheClipDoesNotKeyTheNeck) {
    ActorTemplateBuilder b("unkeyed neck");
    SkeletonNode body;
    body.name = "body";
    body.dofs = {Dof::rotation(glm::vec3(0, 1, 0), -1.0f, 1.0f)};
    b.addNode(body);
    SkeletonNode neck;
    neck.name = "neck";
    neck.parent = 0;
    neck.restTranslation = glm::vec3(0, 1.4f, 0);
    neck.dofs = {Dof::rotation(glm::vec3(0, 1, 0), -1.2f, 1.2f), Dof::rotation(glm::vec3(1, 0, 0), -0.5f, 0.5f)};
    b.addNode(neck);
    ClipChannel c;  // keys the body only
    c.times = {0.0f, 1.0f};
    c.values = {0.0f, 0.1f};
    b.addClip(std::make_shared<const AnimationClip>("sway", std::vector<ClipChannel>{c}));
    const auto tmpl = b.build();
    auto idle = std::make_shared<IdleGroups>(std::vector<double>{60.0, 1e9}, nullptr);
    GazeLayer gaze(idle, GazeLayer::Settings{}, nullptr);
    std::vector<std::uint32_t> slots;
    for (int k = 0; k < 2; ++k) {
        KeyframeBehaviour::Actor a;
        a.tmpl = tmpl;
        a.position = Vec3(1.5 * k, 0.0, 0.0);
        a.heading = k == 0 ? 0.3 : -2.0;
        slots.push_back(gaze.wrap(idle->addPerson(a), tmpl, std::uint64_t(k)));
    }
    const FrameContext context{0.5, 1.0 / 30.0, 15, nullptr};
    gaze.advance(context);
    ASSERT_EQ(gaze.lookingAt(slots[0]), int(slots[1]));
    std::vector<float> kept(tmpl->restDofs().begin(), tmpl->restDofs().end());
    gaze.pose(slots[0], 0.5, 0, *tmpl, {}, kept, nullptr);
    const std::vector<float> first = kept;
    EXPECT_NE(first, std::vector<float>(tmpl->restDofs().begin(), tmpl->restDofs().end())) << "the neck turns";
    for (int again = 0; again < 3; ++again) {
        gaze.pose(slots[0], 0.5, 0, *tmpl, {}, kept, nullptr);
        EXPECT_EQ(kept, first) << "pose " << again + 2 << " turned further";
    }
    // Beyond the gaze's bands the neck is back at the base's pose.
    gaze.pose(slots[0], 0.5, gaze.levelFor(1000.0), *tmpl, {}, kept, nullptr);
    const std::uint32_t yaw = tmpl->dofValueOffset(1, 0);
    EXPECT_EQ(kept[yaw], tmpl->restDofs()[yaw]);
}
