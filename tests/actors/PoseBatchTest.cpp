// The batched pose job (detail/PoseBatch.h) against computeModelTransforms, lane by lane: the same
// bits, the same nodes, the same operation tally, whatever the other lanes hold.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "throng/actors/SeedHumanoid.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/actors/Table3Template.h"
#include "throng/actors/detail/PoseBatch.h"

using namespace throng;

namespace {

// A skeleton with every kind of DOF, rest rotations and scales, and two branches.
std::shared_ptr<const ActorTemplate> everyDofKind() {
    ActorTemplateBuilder b("every-dof-kind");
    const float inf = std::numeric_limits<float>::infinity();
    SkeletonNode root;
    root.name = "root";
    root.dofs = {Dof{DofKind::Position, {}, -inf, inf, {0, 0, 0, 0}}, Dof{DofKind::Orientation, {}, -inf, inf, {0, 0, 0, 1}},
                 Dof{DofKind::Scale, {}, -inf, inf, {1, 1, 1, 0}}};
    const int r = b.addNode(root);
    int parent = r;
    for (int k = 0; k < 5; ++k) {
        SkeletonNode n;
        n.name = "chain" + std::to_string(k);
        n.parent = parent;
        n.restTranslation = glm::vec3(0.1f * float(k), 0.3f, -0.05f);
        n.restRotation = glm::normalize(glm::quat(0.9f, 0.1f * float(k), -0.2f, 0.3f));
        n.restScale = glm::vec3(1.0f, 1.1f, 0.9f);
        n.dofs = {Dof::rotation(glm::normalize(glm::vec3(1, 2, 3)), -0.7f, 0.9f),
                  Dof::translation(glm::vec3(0, 1, 0), -0.2f, 0.2f), Dof::rotation(glm::vec3(0, 0, 1), -1.0f, 1.0f)};
        parent = b.addNode(n);
    }
    SkeletonNode side;
    side.name = "side";
    side.parent = r;
    side.restTranslation = glm::vec3(-0.3f, 0.1f, 0.0f);
    side.dofs = {Dof{DofKind::Orientation, {}, -inf, inf, {0, 0, 0, 1}}};
    const int s = b.addNode(side);
    SkeletonNode tip;
    tip.name = "tip";
    tip.parent = s;
    tip.dofs = {Dof::rotation(glm::vec3(1, 0, 0), -2.0f, 2.0f)};
    b.addNode(tip);
    return b.build();
}

// Random DOF values, a third of them beyond their limits (clamped by both jobs).
std::vector<float> randomDofs(const ActorTemplate& t, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-1.5f, 1.5f);
    std::vector<float> v(t.dofValueCount());
    for (float& x : v) x = u(rng);
    return v;
}

// Random active flags (the root always active), so lanes differ in which subtrees they skip.
std::vector<std::uint8_t> randomActive(const ActorTemplate& t, std::mt19937& rng) {
    std::bernoulli_distribution on(0.75);
    std::vector<std::uint8_t> a(t.nodeCount());
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = i == 0 || on(rng);
    return a;
}

bool sameBits(const Affine& a, const Affine& b) { return std::memcmp(&a, &b, sizeof(Affine)) == 0; }

// A transform no job writes: entries left untouched keep it.
Affine sentinel() {
    Affine a;
    a.translation = glm::vec3(-777.0f);
    return a;
}

// Poses `lanes` actors of `t` (each with its own values and flags, null flags on odd lanes when
// `allOnOdd`) in one batch and each alone, and compares everything.
void checkBatch(const ActorTemplate& t, std::size_t laneCount, std::mt19937& rng, bool allOnOdd) {
    const std::size_t n = t.nodeCount();
    std::vector<std::vector<float>> dofs;
    std::vector<std::vector<std::uint8_t>> active;
    std::vector<std::vector<Affine>> batched(laneCount, std::vector<Affine>(n, sentinel()));
    std::vector<detail::PoseLane> lanes;
    for (std::size_t k = 0; k < laneCount; ++k) {
        dofs.push_back(randomDofs(t, rng));
        active.push_back(randomActive(t, rng));
    }
    for (std::size_t k = 0; k < laneCount; ++k) {
        const bool all = allOnOdd && k % 2 == 1;
        lanes.push_back({dofs[k].data(), all ? nullptr : active[k].data(), batched[k].data()});
    }
    detail::PoseBatchWorkspace workspace;
    std::uint32_t evaluated[detail::kPoseLanes] = {};
    OpTally batchOps;
    detail::computeModelTransformsBatch(t, lanes, workspace, std::span(evaluated, laneCount), &batchOps);
    OpTally aloneOps;
    for (std::size_t k = 0; k < laneCount; ++k) {
        const bool all = allOnOdd && k % 2 == 1;
        std::vector<Affine> alone(n, sentinel());
        const std::size_t count =
            computeModelTransforms(t, dofs[k], all ? std::span<const std::uint8_t>() : std::span<const std::uint8_t>(active[k]), alone, &aloneOps);
        EXPECT_EQ(evaluated[k], count) << t.name() << ", lane " << k << " of " << laneCount;
        for (std::size_t i = 0; i < n; ++i)
            EXPECT_TRUE(sameBits(batched[k][i], alone[i])) << t.name() << ", lane " << k << " of " << laneCount << ", node " << i;
    }
    EXPECT_EQ(batchOps.mults, aloneOps.mults);
    EXPECT_EQ(batchOps.adds, aloneOps.adds);
    EXPECT_EQ(batchOps.divs, aloneOps.divs);
    EXPECT_EQ(batchOps.sqrts, aloneOps.sqrts);
}

TEST(PoseBatch, EveryLaneMatchesThePoseJobToTheBit) {
    std::mt19937 rng(11);
    const std::shared_ptr<const ActorTemplate> templates[] = {everyDofKind(), makeSeedHumanoid(), makeTable3Template()};
    for (const auto& t : templates)
        for (std::size_t lanes = 1; lanes <= detail::kPoseLanes; ++lanes)
            for (int round = 0; round < 20; ++round) checkBatch(*t, lanes, rng, round % 2 == 1);
}

TEST(PoseBatch, ALaneOfNonFiniteValuesLeavesTheOthersAlone) {
    const auto t = everyDofKind();
    std::mt19937 rng(5);
    std::vector<float> good = randomDofs(*t, rng);
    std::vector<float> bad(t->dofValueCount(), std::numeric_limits<float>::quiet_NaN());
    std::vector<Affine> goodOut(t->nodeCount(), sentinel()), badOut(t->nodeCount(), sentinel()), alone(t->nodeCount(), sentinel());
    const detail::PoseLane lanes[] = {{bad.data(), nullptr, badOut.data()}, {good.data(), nullptr, goodOut.data()}};
    detail::PoseBatchWorkspace workspace;
    std::uint32_t evaluated[2];
    detail::computeModelTransformsBatch(*t, lanes, workspace, evaluated, nullptr);
    computeModelTransforms(*t, good, {}, alone);
    for (std::size_t i = 0; i < t->nodeCount(); ++i) {
        EXPECT_TRUE(sameBits(goodOut[i], alone[i])) << "node " << i;
        EXPECT_TRUE(std::isnan(badOut[i].translation.x)) << "node " << i;  // NaN in, NaN out: nothing hides it
    }
}

TEST(PoseBatch, ANodeNoLaneComputesSkipsItsSubtree) {
    const auto t = everyDofKind();
    std::mt19937 rng(3);
    std::vector<float> dofs = randomDofs(*t, rng);
    std::vector<std::uint8_t> active(t->nodeCount(), 1);
    active[2] = 0;  // chain1: its descendants are flagged active but hang under an inactive node
    std::vector<Affine> out(t->nodeCount(), sentinel());
    const detail::PoseLane lanes[] = {{dofs.data(), active.data(), out.data()}, {dofs.data(), active.data(), out.data()}};
    detail::PoseBatchWorkspace workspace;
    std::uint32_t evaluated[2];
    detail::computeModelTransformsBatch(*t, lanes, workspace, evaluated, nullptr);
    for (std::size_t i = 2; i < t->subtreeEnd(2); ++i) EXPECT_TRUE(sameBits(out[i], sentinel())) << "node " << i;
    EXPECT_EQ(evaluated[0], t->nodeCount() - (t->subtreeEnd(2) - 2));
    EXPECT_EQ(evaluated[1], evaluated[0]);
}

}  // namespace
