// FMULT tallies of the actors' kernels (DOF evaluation, matrices, pose, internal spheres, skin
// palettes, detail distances, key-frame sampling, Reference Point paths) checked against the
// operations they execute on counting numbers, over inputs that take every branch: DOFs within and
// beyond their limits, skeletal LOD switching nodes off, nodes without geometry, keys before,
// between and after, every interpolation. The counting run must give the production result bit
// for bit.

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "KernelCheck.h"
#include "throng/actors/AnimationClip.h"
#include "throng/actors/ProceduralGait.h"
#include "throng/actors/RefpointPath.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/actors/Table3Template.h"
#include "throng/actors/detail/ClipKernels.h"
#include "throng/actors/detail/GaitKernels.h"
#include "throng/actors/detail/PoseKernels.h"
#include "throng/actors/detail/RefpointKernel.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/MeshShapes.h"
#include "throng/scenegraph/detail/BoundingSphereImpl.h"

using namespace throng;
using namespace throng::counting;

namespace {

using CAffine = BasicAffine<CFloat>;
using CSphere = BasicBoundingSphere<CDouble>;
using CMat4 = glm::mat<4, 4, CDouble>;
using CFMat4 = glm::mat<4, 4, CFloat>;
using CVec3 = glm::vec<3, CDouble>;

CAffine counted(const Affine& a) { return CAffine{glm::mat<3, 3, CFloat>(a.linear), glm::vec<3, CFloat>(a.translation)}; }
std::vector<CFloat> counted(std::span<const float> v) { return std::vector<CFloat>(v.begin(), v.end()); }

template <class C, class P, int N>
void expectSameComponents(const C& c, const P& p, const std::string& what) {
    for (int i = 0; i < N; ++i) EXPECT_EQ(c[i].value(), p[i]) << what << " component " << i;
}
void expectSame(const CAffine& c, const Affine& a, const std::string& what) {
    for (int col = 0; col < 3; ++col) expectSameComponents<glm::vec<3, CFloat>, glm::vec3, 3>(c.linear[col], a.linear[col], what);
    expectSameComponents<glm::vec<3, CFloat>, glm::vec3, 3>(c.translation, a.translation, what);
}
template <class CM, class M>
void expectSameMatrix(const CM& c, const M& m, const std::string& what) {
    for (int col = 0; col < 4; ++col)
        for (int row = 0; row < 4; ++row) EXPECT_EQ(c[col][row].value(), m[col][row]) << what;
}
void expectSame(const CSphere& c, const BoundingSphere& s, const std::string& what) {
    EXPECT_EQ(c.radius().value(), s.radius()) << what;
    for (int i = 0; i < 3; ++i) EXPECT_EQ(c.center()[i].value(), s.center()[i]) << what;
}

// Five nodes using every DOF kind, limits that clamp, a node without geometry and a skin.
std::shared_ptr<const ActorTemplate> everyDofKind() {
    const float inf = std::numeric_limits<float>::infinity();
    SkeletonNode root;
    root.name = "root";
    root.dofs = {Dof{DofKind::Position, {}, -inf, inf, {0, 0, 0, 0}}, Dof{DofKind::Orientation, {}, -inf, inf, {0, 0, 0, 1}},
                 Dof{DofKind::Scale, {}, -inf, inf, {1, 1, 1, 0}}};
    root.geometrySphere = BoundingSphere(Vec3(0, 0.5, 0), 0.6);
    SkeletonNode arm;
    arm.name = "arm";
    arm.parent = 0;
    arm.restTranslation = glm::vec3(0.2f, 1.0f, 0.0f);
    arm.restRotation = glm::normalize(glm::quat(0.9f, 0.1f, 0.3f, 0.0f));
    arm.dofs = {Dof::rotation(glm::normalize(glm::vec3(0.6f, 0.8f, 0.0f)), -0.5f, 0.7f),
                Dof::translation(glm::vec3(0, 1, 0), -0.1f, 0.2f)};
    arm.deactivationDistance = 40.0;
    arm.geometrySphere = BoundingSphere(Vec3(0, 0.3, 0), 0.35);
    SkeletonNode hand;
    hand.name = "hand";
    hand.parent = 1;
    hand.restTranslation = glm::vec3(0, 0.6f, 0);
    hand.restScale = glm::vec3(1.0f, 1.2f, 0.9f);
    hand.dofs = {Dof::rotation(glm::vec3(1, 0, 0), -1.0f, 1.0f), Dof::rotation(glm::vec3(0, 0, 1), -0.3f, 1.2f)};
    hand.deactivationDistance = 20.0;
    hand.geometrySphere = BoundingSphere(Vec3(0, 0.1, 0), 0.12);
    SkeletonNode tail;  // no DOF, no geometry: an empty internal sphere
    tail.name = "tail";
    tail.parent = 0;
    tail.restTranslation = glm::vec3(0, -0.2f, -0.3f);
    SkeletonNode leg;
    leg.name = "leg";
    leg.parent = 0;
    leg.restTranslation = glm::vec3(0.1f, -0.1f, 0);
    leg.dofs = {Dof::rotation(glm::vec3(1, 0, 0), -1.5f, 1.5f, 0.2f)};
    leg.geometrySphere = BoundingSphere(Vec3(0, -0.4, 0), 0.45);
    leg.inverseBind[3] = glm::vec4(-0.1f, 0.1f, 0.0f, 1.0f);
    ActorTemplateBuilder b("everyDofKind");
    for (SkeletonNode* n : {&root, &arm, &hand, &tail, &leg}) b.addNode(*n);
    b.addSkin(Skin{"skin", {0, 1, 2, 3, 4}});
    b.rootGeometry().addLevel(100.0, std::make_shared<MeshDrawable>(makeBox("body", glm::vec3(0, 0.5f, 0), glm::vec3(0.2f, 0.5f, 0.1f))));
    return b.build();
}

struct Random {
    std::mt19937_64 rng{77};
    float uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(rng); }
    // DOF values of `t`: axis values from beyond their lower limit to beyond their upper one.
    std::vector<float> dofs(const ActorTemplate& t) {
        std::vector<float> v(t.restDofs().begin(), t.restDofs().end());
        for (std::size_t i = 0; i < t.nodeCount(); ++i) {
            std::uint32_t at = t.dofOffset(i);
            for (const Dof& d : t.nodes()[i].dofs) {
                switch (d.kind) {
                    case DofKind::RotateAxis:
                    case DofKind::TranslateAxis: {
                        const float lo = std::max(d.min, -3.0f), hi = std::min(d.max, 3.0f);
                        v[at] = uniform(lo - 0.5f * (hi - lo), hi + 0.5f * (hi - lo));
                        break;
                    }
                    case DofKind::Orientation: {
                        const glm::quat q = glm::normalize(glm::quat(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)));
                        v[at] = q.x, v[at + 1] = q.y, v[at + 2] = q.z, v[at + 3] = q.w;
                        break;
                    }
                    case DofKind::Position:
                        for (int k = 0; k < 3; ++k) v[at + std::uint32_t(k)] = uniform(-2, 2);
                        break;
                    case DofKind::Scale:
                        for (int k = 0; k < 3; ++k) v[at + std::uint32_t(k)] = uniform(0.5f, 1.5f);
                        break;
                }
                at += std::uint32_t(dofValueCount(d.kind));
            }
        }
        return v;
    }
};

std::vector<std::shared_ptr<const ActorTemplate>> templates() {
    return {everyDofKind(), makeTable3Template(), makeSeedHumanoid()};
}

// Active flags of `t` at several distances: every node, skeletal LOD at work, none.
std::vector<std::vector<std::uint8_t>> activeSets(const ActorTemplate& t) {
    std::vector<std::vector<std::uint8_t>> sets = {{}};
    for (double d : {1.0, 15.0, 30.0, 60.0, 150.0, 1e9}) {
        std::vector<std::uint8_t> a(t.nodeCount());
        computeActiveNodes(t, d * d, a);
        sets.push_back(a);
    }
    return sets;
}

}  // namespace

TEST(CountedKernels, AffineProduct) {
    THRONG_SKIP_WITHOUT_COUNTING();
    Random r;
    const auto t = everyDofKind();
    std::vector<Affine> model(t->nodeCount());
    computeModelTransforms(*t, r.dofs(*t), {}, model);
    CAffine ab;
    expectTallyMatchesExecuted("compose", [&](OpTally* hand) { ab = compose(counted(model[2]), counted(model[1]), hand); });
    expectSame(ab, model[2] * model[1], "compose");
}

TEST(CountedKernels, NodeLocalTransformEveryDofKindClampedOrNot) {
    THRONG_SKIP_WITHOUT_COUNTING();
    Random r;
    for (const auto& t : templates())
        for (int trial = 0; trial < 40; ++trial) {
            const std::vector<float> dofs = r.dofs(*t);
            const std::vector<CFloat> cdofs = counted(dofs);
            for (std::size_t i = 0; i < t->nodeCount(); ++i) {
                const std::string what = t->name() + " node " + t->nodes()[i].name;
                CAffine local;
                expectTallyMatchesExecuted(what, [&](OpTally* hand) {
                    local = detail::nodeLocalTransform(t->nodes()[i], cdofs.data() + t->dofOffset(i), hand);
                });
                expectSame(local, nodeLocalTransform(t->nodes()[i], dofs.data() + t->dofOffset(i)), what);
            }
        }
}

TEST(CountedKernels, ModelTransformsInternalSpheresAndSkinPaletteUnderSkeletalLod) {
    THRONG_SKIP_WITHOUT_COUNTING();
    Random r;
    for (const auto& t : templates()) {
        const std::size_t n = t->nodeCount();
        for (const auto& active : activeSets(*t)) {
            const std::string what = t->name() + " with " +
                                     (active.empty() ? std::string("every node") : std::to_string(std::count(active.begin(), active.end(), 1)) + " active");
            const std::vector<float> dofs = r.dofs(*t);
            const std::vector<CFloat> cdofs = counted(dofs);
            std::vector<Affine> model(n);
            std::vector<CAffine> cmodel(n);
            std::size_t evaluated = 0;
            expectTallyMatchesExecuted("computeModelTransforms, " + what, [&](OpTally* hand) {
                evaluated = detail::computeModelTransforms(*t, std::span<const CFloat>(cdofs), active, std::span<CAffine>(cmodel), hand);
            });
            EXPECT_EQ(evaluated, computeModelTransforms(*t, dofs, active, model));
            for (std::size_t i = 0; i < n; ++i)
                if (active.empty() || active[i]) expectSame(cmodel[i], model[i], what);

            std::vector<BoundingSphere> geometry(n), subtree(n);
            std::vector<CSphere> cgeometry(n), csubtree(n);
            CSphere whole;
            expectTallyMatchesExecuted("computeInternalSpheres, " + what, [&](OpTally* hand) {
                whole = detail::computeInternalSpheres(*t, std::span<const CAffine>(cmodel), active, std::span<CSphere>(cgeometry),
                                                       std::span<CSphere>(csubtree), hand);
            });
            expectSame(whole, computeInternalSpheres(*t, model, active, geometry, subtree), what);

            for (const Skin& skin : t->skins()) {
                std::vector<glm::mat4> palette(skin.joints.size());
                std::vector<CFMat4> cpalette(skin.joints.size());
                expectTallyMatchesExecuted("computeSkinPalette, " + what, [&](OpTally* hand) {
                    detail::computeSkinPalette(*t, skin, std::span<const CAffine>(cmodel), active, std::span<CFMat4>(cpalette), hand);
                });
                computeSkinPalette(*t, skin, model, active, palette);
                for (std::size_t k = 0; k < palette.size(); ++k) expectSameMatrix(cpalette[k], palette[k], what);
            }
        }
    }
}

TEST(CountedKernels, SkinPaletteWithNoActiveAncestor) {
    THRONG_SKIP_WITHOUT_COUNTING();
    const auto t = everyDofKind();
    const std::vector<std::uint8_t> none(t->nodeCount(), 0);
    std::vector<CAffine> cmodel(t->nodeCount());
    std::vector<CFMat4> cpalette(t->skins()[0].joints.size());
    expectTallyMatchesExecuted("computeSkinPalette, no node active", [&](OpTally* hand) {
        detail::computeSkinPalette(*t, t->skins()[0], std::span<const CAffine>(cmodel), none, std::span<CFMat4>(cpalette), hand);
    });
}

TEST(CountedKernels, DetailAndEyeDistanceRootPoseAndPartSphere) {
    THRONG_SKIP_WITHOUT_COUNTING();
    Random r;
    for (int i = 0; i < 30; ++i) {
        RootPose root;
        root.translation = glm::vec3(r.uniform(-1, 1), r.uniform(0, 2), r.uniform(-1, 1));
        root.orientation = glm::normalize(glm::quat(r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1), r.uniform(-1, 1)));
        const BasicRootPose<CFloat> croot{glm::vec<3, CFloat>(root.translation), glm::qua<CFloat>(root.orientation)};
        CMat4 m;
        expectTallyMatchesExecuted("rootPoseMatrix", [&](OpTally* hand) { m = detail::rootPoseMatrix(croot, hand); });
        const Mat4 skls = rootPoseMatrix(root);
        expectSameMatrix(m, skls, "rootPoseMatrix");

        const Vec3 eye(r.uniform(-100, 100), r.uniform(0, 10), r.uniform(-100, 100));
        const double scale2 = r.uniform(0.1f, 4.0f);
        const float priority = r.uniform(0.5f, 2.0f);
        CDouble d2, d;
        expectTallyMatchesExecuted("detailDistanceSquared", [&](OpTally* hand) {
            d2 = detail::detailDistanceSquared(m, CVec3(eye), CDouble(scale2), CDouble(CFloat(priority)), hand);
        });
        EXPECT_EQ(d2.value(), detailDistanceSquared(skls, eye, scale2, priority));
        expectTallyMatchesExecuted("eyeDistance", [&](OpTally* hand) { d = detail::eyeDistance(m, CVec3(eye), hand); });
        EXPECT_EQ(d.value(), eyeDistance(skls, eye));

        const auto t = everyDofKind();
        std::vector<Affine> model(t->nodeCount());
        computeModelTransforms(*t, r.dofs(*t), {}, model);
        const BoundingSphere local(Vec3(0.1, 0.2, 0.3), 0.25);
        CSphere part;
        expectTallyMatchesExecuted("partWorldSphere", [&](OpTally* hand) {
            part = detail::partWorldSphere(CSphere(local), counted(model[2]), m, hand);
        });
        expectSame(part, partWorldSphere(local, model[2], skls), "partWorldSphere");
    }
}

TEST(CountedKernels, ReferencePointPaths) {
    THRONG_SKIP_WITHOUT_COUNTING();
    for (const RefpointPath& p : {RefpointPath{Vec3(1, 0, 2), 0.3, 0.0, 0.0}, RefpointPath{Vec3(-4, 0, 7), 1.1, 5.0, 1.4}})
        for (double time : {0.0, 1.7, 1e5}) {
            CMat4 m;
            expectTallyMatchesExecuted("RefpointPath::at", [&](OpTally* hand) {
                m = detail::refpointMatrix(CVec3(p.center), CDouble(p.heading), CDouble(p.radius), CDouble(p.speed), CDouble(time), hand);
            });
            expectSameMatrix(m, p.at(time), "RefpointPath::at");
        }
}

TEST(CountedKernels, ProceduralGaitEveryLevel) {
    THRONG_SKIP_WITHOUT_COUNTING();
    ProceduralGait::Actor actor;
    actor.phase = 0.7;
    actor.stepFrequency = 1.9;
    ProceduralGait gait;
    const std::uint32_t slot = gait.addActor(actor);
    for (const auto& t : templates())
        for (int level : {0, 1, 2})
            for (double time : {0.3, 123.4})
                for (const auto& active : activeSets(*t)) {
                    const std::string what = t->name() + " level " + std::to_string(level) + " at " + std::to_string(time);
                    std::vector<float> dofs(t->restDofs().begin(), t->restDofs().end());
                    std::vector<CFloat> cdofs = counted(dofs);
                    expectTallyMatchesExecuted("ProceduralGait::pose " + what, [&](OpTally* hand) {
                        detail::gaitPose(actor, CDouble(time), level, *t, active, std::span<CFloat>(cdofs), hand);
                    });
                    gait.pose(slot, time, level, *t, active, dofs, nullptr);
                    for (std::size_t i = 0; i < dofs.size(); ++i) EXPECT_EQ(cdofs[i].value(), dofs[i]) << what << " value " << i;
                }
    for (double time : {0.0, 0.41, 1e5}) {
        CDouble bob;
        expectTallyMatchesExecuted("ProceduralGait::skeletonRoot", [&](OpTally* hand) {
            bob = detail::gaitBob(CDouble(actor.stepFrequency), CDouble(actor.phase), CDouble(time), hand);
        });
        EXPECT_EQ(static_cast<float>(bob.value()), gait.skeletonRoot(slot, time, 0, nullptr).translation.y);
    }
}

namespace {

ClipChannel channel(Interpolation interpolation, std::vector<float> times, std::vector<float> values) {
    ClipChannel c;
    c.interpolation = interpolation;
    c.times = std::move(times);
    c.values = std::move(values);
    return c;
}

// Samples one channel at `t` on counting numbers and on float; checks tally and values.
void checkChannel(const ClipChannel& c, int width, bool orientation, float t, bool holdKeys, const std::string& what) {
    std::vector<CFloat> out(static_cast<std::size_t>(width));
    expectTallyMatchesExecuted(what, [&](OpTally* hand) {
        detail::sampleChannel(c, width, orientation, CFloat(t), out.data(), hand, holdKeys);
    });
    std::vector<float> expected(static_cast<std::size_t>(width));
    detail::sampleChannel(c, width, orientation, t, expected.data(), nullptr, holdKeys);
    for (std::size_t j = 0; j < expected.size(); ++j) EXPECT_EQ(out[j].value(), expected[j]) << what << " value " << j;
}

// Times before the first key, on every key, between keys and after the last.
std::vector<float> sampleTimes(const std::vector<float>& keys) {
    std::vector<float> t = {keys.front() - 0.25f, keys.back() + 0.5f};
    for (std::size_t k = 0; k < keys.size(); ++k) {
        t.push_back(keys[k]);
        if (k + 1 < keys.size()) t.push_back(0.3f * keys[k] + 0.7f * keys[k + 1]);
    }
    return t;
}

}  // namespace

TEST(CountedKernels, ClipChannelsEveryInterpolationAndKeyCount) {
    THRONG_SKIP_WITHOUT_COUNTING();
    Random r;
    // Scalar and vector channels, 1 to 17 keys (every depth of the binary search).
    for (std::size_t keys : {1u, 2u, 3u, 4u, 5u, 7u, 8u, 9u, 16u, 17u})
        for (int width : {1, 3})
            for (Interpolation interpolation : {Interpolation::Step, Interpolation::Linear, Interpolation::CubicSpline}) {
                std::vector<float> times, values;
                for (std::size_t k = 0; k < keys; ++k) {
                    times.push_back(0.5f + 0.4f * float(k) + r.uniform(0.0f, 0.3f));
                    for (std::size_t j = 0; j < valuesPerKey(interpolation, width); ++j) values.push_back(r.uniform(-2, 2));
                }
                const ClipChannel c = channel(interpolation, times, values);
                for (float t : sampleTimes(times))
                    for (bool hold : {false, true})
                        checkChannel(c, width, false, t, hold,
                                     std::to_string(keys) + " keys, width " + std::to_string(width) + ", interpolation " +
                                         std::to_string(int(interpolation)) + ", t " + std::to_string(t) + (hold ? ", keys held" : ""));
            }
}

TEST(CountedKernels, ClipOrientationsSlerpBranchesAndCubicNormalisation) {
    THRONG_SKIP_WITHOUT_COUNTING();
    // Keys (x, y, z, w): identity; a tiny turn (nearly equal: linear blend); a large turn (slerp);
    // the opposite sign of a nearby rotation (the short way round, then nearly equal).
    const glm::quat q0(1, 0, 0, 0), q1 = glm::angleAxis(0.01f, glm::vec3(0, 1, 0)), q2 = glm::angleAxis(2.0f, glm::vec3(0, 1, 0)),
                    q3 = -glm::angleAxis(2.02f, glm::vec3(0, 1, 0));
    ASSERT_GT(glm::dot(q0, q1), 0.9995f);
    ASSERT_LT(glm::dot(q1, q2), 0.9995f);
    ASSERT_LT(glm::dot(q2, q3), 0.0f);
    ASSERT_GT(-glm::dot(q2, q3), 0.9995f);
    std::vector<float> values;
    for (const glm::quat& q : {q0, q1, q2, q3}) values.insert(values.end(), {q.x, q.y, q.z, q.w});
    const ClipChannel linear = channel(Interpolation::Linear, {0.0f, 1.0f, 2.0f, 3.0f}, values);
    for (float t : sampleTimes(linear.times)) checkChannel(linear, 4, true, t, false, "slerp at t " + std::to_string(t));
    // Cubic spline orientations are renormalised, unless the spline passes through zero.
    std::vector<float> cubic;
    for (const glm::quat& q : {q0, q2}) cubic.insert(cubic.end(), {0.1f, 0.0f, -0.1f, 0.0f, q.x, q.y, q.z, q.w, 0.0f, 0.2f, 0.0f, 0.1f});
    const ClipChannel spline = channel(Interpolation::CubicSpline, {0.0f, 1.0f}, cubic);
    for (float t : {0.25f, 0.5f, 0.9f}) checkChannel(spline, 4, true, t, false, "cubic orientation at t " + std::to_string(t));
    const ClipChannel zero = channel(Interpolation::CubicSpline, {0.0f, 1.0f}, std::vector<float>(24, 0.0f));
    checkChannel(zero, 4, true, 0.5f, false, "cubic orientation through zero");
}

TEST(CountedKernels, ClipSamplingLocalTimeAndRoot) {
    THRONG_SKIP_WITHOUT_COUNTING();
    // The Table 3 actor's clip (80 linear rotation channels), and a clip of every DOF kind with
    // Skeleton Root channels.
    const auto table3 = makeTable3Template();
    const auto every = everyDofKind();
    std::vector<ClipChannel> channels;
    auto add = [&](ClipChannel c, std::uint32_t node, std::uint32_t dof) {
        c.node = node, c.dof = dof;
        channels.push_back(std::move(c));
    };
    add(channel(Interpolation::Linear, {0.0f, 1.0f, 2.0f}, {0, 0, 0, 1, 1, 1, 0, 2, 0}), 0, 0);                        // position
    add(channel(Interpolation::Linear, {0.0f, 2.0f}, {0, 0, 0, 1, 0, 0.7071f, 0, 0.7071f}), 0, 1);                     // orientation
    add(channel(Interpolation::Step, {0.0f, 1.0f}, {1, 1, 1, 1.2f, 0.8f, 1}), 0, 2);                                     // scale
    add(channel(Interpolation::CubicSpline, {0.0f, 1.5f}, {0, -0.2f, 0.1f, 0.1f, 0.6f, 0}), 1, 0);                      // rotation
    add(channel(Interpolation::Linear, {0.5f, 1.0f}, {0.0f, 0.1f}), 1, 1);                                              // translation
    add(channel(Interpolation::Linear, {0.0f, 1.0f, 2.5f}, {-1.2f, 0.0f, 1.4f}), 4, 0);                                 // clamped rotation
    ClipChannel rootT = channel(Interpolation::Linear, {0.0f, 2.5f}, {0, 0, 0, 0, 0.1f, 1});
    rootT.target = ClipChannel::Target::RootTranslation;
    channels.push_back(rootT);
    ClipChannel rootR = channel(Interpolation::Linear, {0.0f, 2.5f}, {0, 0, 0, 1, 0, 0.3827f, 0, 0.9239f});
    rootR.target = ClipChannel::Target::RootOrientation;
    channels.push_back(rootR);
    const AnimationClip everyClip("every", channels);
    const AnimationClip empty("empty", {});
    struct Case {
        const ActorTemplate* tmpl;
        const AnimationClip* clip;
    };
    for (const Case& c : {Case{table3.get(), table3->clips()[0].get()}, Case{every.get(), &everyClip}, Case{every.get(), &empty}})
        for (double t : {-3.7, 0.0, 0.75, 1.25, 2.6, 1e6 + 0.3})
            for (bool loop : {true, false})
                for (const auto& active : activeSets(*c.tmpl))
                    for (bool hold : {false, true}) {
                        const std::string what = c.clip->name() + " at " + std::to_string(t) + (loop ? " looped" : "") +
                                                 (hold ? ", keys held" : "") + ", " + std::to_string(active.size()) + " flags";
                        std::vector<float> dofs(c.tmpl->restDofs().begin(), c.tmpl->restDofs().end());
                        std::vector<CFloat> cdofs = counted(dofs);
                        std::size_t written = 0;
                        expectTallyMatchesExecuted("sample " + what, [&](OpTally* hand) {
                            written = detail::sampleClip(*c.clip, *c.tmpl, CDouble(t), loop, active, std::span<CFloat>(cdofs), hand, hold);
                        });
                        EXPECT_EQ(written, c.clip->sample(*c.tmpl, t, loop, active, dofs, nullptr, hold));
                        for (std::size_t i = 0; i < dofs.size(); ++i) EXPECT_EQ(cdofs[i].value(), dofs[i]) << what << " value " << i;
                        BasicRootPose<CFloat> root;
                        expectTallyMatchesExecuted("sampleRoot " + what, [&](OpTally* hand) {
                            root = detail::sampleClipRoot<CFloat>(*c.clip, CDouble(t), loop, hand, hold);
                        });
                        const RootPose expected = c.clip->sampleRoot(t, loop, nullptr, hold);
                        for (int k = 0; k < 3; ++k) EXPECT_EQ(root.translation[k].value(), expected.translation[k]) << what;
                        for (int k = 0; k < 4; ++k) EXPECT_EQ(root.orientation[k].value(), expected.orientation[k]) << what;
                    }
}
