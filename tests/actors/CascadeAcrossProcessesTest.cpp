// The cascade split over processes that each pose their own actors (Behaviour::presence: the
// others are absent there), each sending its draw items as records (DrawRecords.h): merged in the
// drawing process, the list is item for item the one a process holding every actor makes, frame
// after frame (impostor hysteresis and occlusion included), and the Table-2 counts add up to its.

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "throng/actors/ActorDrawReferences.h"
#include "throng/actors/ActorGroup.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/DrawRecords.h"
#include "throng/scenegraph/Geometry.h"
#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/Occluder.h"

using namespace throng;

namespace {

// Walkers of which a process holds some (`here`, per slot; empty: all).
class OwnWalkers : public KeyframeBehaviour {
public:
    std::vector<std::uint8_t> here;
    bool presence(std::span<const std::uint32_t> slots, std::span<std::uint8_t> present) const override {
        if (here.empty()) return true;
        for (std::size_t k = 0; k < slots.size(); ++k) present[k] = here[slots[k]];
        return false;
    }
};

// One process's copy of the scene: a street (the drawing process only), a wall, then two groups of
// walkers with roaming bounds, as every process builds them.
struct World {
    Crowd crowd;
    std::shared_ptr<OwnWalkers> walkers = std::make_shared<OwnWalkers>();
    std::shared_ptr<Group> root = std::make_shared<Group>();
    std::unique_ptr<ActorProcessor> processor;
    DrawReferences refs;
};

constexpr std::size_t kWalkers = 1200;
constexpr double kExtent = 160.0;

std::shared_ptr<const Drawable> impostor() {
    static const auto d = std::make_shared<Drawable>("impostor", BoundingSphere(Vec3(0.0, 0.9, 0.0), 1.0), 2);
    return d;
}

std::unique_ptr<World> world(bool draws) {
    static const auto humanoid = makeSeedHumanoid();
    auto w = std::make_unique<World>();
    if (draws) {
        static const auto street = std::make_shared<Drawable>("street", BoundingSphere(Vec3(0.0), 100.0), 12);
        w->root->addChild(std::make_shared<Geometry>(street));
    }
    // Every process tests against the same occlusion buffer (here each draws it from the same wall).
    w->root->addChild(std::make_shared<Occluder>(std::vector<AxisBox>{AxisBox{glm::vec3(-30, 0, -1), glm::vec3(30, 12, 1)}},
                                                 AxisBox{glm::vec3(-31, -1, -2), glm::vec3(31, 13, 2)}));
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<ActorId> ids[2];
    for (std::size_t i = 0; i < kWalkers; ++i) {
        KeyframeBehaviour::Actor a;
        a.tmpl = humanoid;
        a.clip = std::max(humanoid->findClip("walk"), 0);
        a.position = Vec3(kExtent * (u(rng) - 0.5), 0.0, kExtent * (u(rng) - 0.5));
        a.heading = 6.283 * u(rng);
        a.pathRadius = 2.0 + 6.0 * u(rng);
        a.pathSpeed = 1.0 + 0.5 * u(rng);
        a.timeOffset = 2.0 * u(rng);
        ids[i % 2].push_back(w->crowd.add(humanoid, w->walkers, w->walkers->addActor(a)));
    }
    for (auto& members : ids) {
        auto group = w->crowd.makeGroupNode(members);
        group->setRoamingBound(BoundingSphere(Vec3(0.0), kExtent));
        w->root->addChild(group);
    }
    w->processor = std::make_unique<ActorProcessor>(w->crowd);
    w->processor->setImpostor(*humanoid, impostor());
    w->processor->setImpostorDistance(45.0, 4.0);
    w->processor->setOcclusion(OcclusionSettings{});
    w->refs = actorDrawReferences(w->crowd, *w->root, *w->processor);
    return w;
}

// The camera of frame `f`: walking in and turning, so that actors cross the impostor distance and
// the view's edges, and some pass behind the wall.
Camera cameraAt(int f) {
    Camera camera;
    camera.setPerspective(1.0, 16.0 / 9.0, 0.2, 400.0);
    const double z = 80.0 - 3.0 * f, turn = 0.05 * f;
    camera.setLookAt(Vec3(5.0 * std::sin(turn), 1.7, z), Vec3(20.0 * std::sin(turn), 1.5, z - 50.0), Vec3(0, 1, 0));
    return camera;
}

}  // namespace

// Two and three processes, actors owned by where they start (as a rank owns its regions' walkers).
TEST(CascadeAcrossProcesses, MergedRecordsAreTheListOfOneProcessHoldingEveryActor) {
    for (int processes : {2, 3}) {
        SCOPED_TRACE(std::to_string(processes) + " processes");
        auto whole = world(true);
        std::vector<std::unique_ptr<World>> parts;
        for (int p = 0; p < processes; ++p) parts.push_back(world(p == 0));
        // Process p holds the walkers starting in stripe p of the ground (x), whatever group they are in.
        for (int p = 0; p < processes; ++p) {
            parts[std::size_t(p)]->walkers->here.assign(kWalkers, 0);
            for (std::size_t i = 0; i < kWalkers; ++i) {
                const double x = whole->walkers->referencePoint(std::uint32_t(i), FrameContext{}, nullptr)[3].x;
                const int stripe = std::min(processes - 1, int((x / kExtent + 0.5) * processes));
                parts[std::size_t(p)]->walkers->here[i] = stripe == p;
            }
        }
        DrawRecordMerger merger;
        std::uint64_t impostorItems = 0, occluded = 0;
        for (int f = 0; f < 24; ++f) {
            SCOPED_TRACE("frame " + std::to_string(f));
            const Camera camera = cameraAt(f);
            const double time = 0.1 * f;
            const ActorFrameStatistics one = whole->processor->processFrame(*whole->root, camera, time);
            std::vector<std::vector<std::byte>> bytes(static_cast<std::size_t>(processes));
            ActorFrameStatistics sum;
            for (int p = 0; p < processes; ++p) {
                World& part = *parts[std::size_t(p)];
                const ActorFrameStatistics& s = part.processor->processFrame(*part.root, camera, time);
                writeDrawRecords(part.processor->drawList(), part.refs, bytes[std::size_t(p)]);
                addShare(sum, s);
            }
            // The drawing process: its own items of no actor, then everyone's merged.
            DrawList merged;
            for (const DrawItem& item : parts[0]->processor->drawList().items())
                if (item.actor == kNoActor) merged.add(item, item.drawable->primitiveCount());
            std::vector<std::span<const std::byte>> messages(bytes.begin(), bytes.end());
            merger.merge(messages, parts[0]->refs, merged);

            const DrawList& expected = whole->processor->drawList();
            ASSERT_EQ(merged.size(), expected.size());
            EXPECT_EQ(merged.primitiveCount(), expected.primitiveCount());
            auto m = merged.items().begin();
            for (const DrawItem& e : expected.items()) {
                const DrawItem& i = *m++;
                ASSERT_EQ(i.actor, e.actor);
                ASSERT_EQ(i.part, e.part);
                EXPECT_EQ(i.drawable, e.drawable);
                EXPECT_EQ(parts[0]->refs.numberOf(i.node), whole->refs.numberOf(e.node));
                EXPECT_TRUE(i.world == e.world) << "actor " << e.actor << " part " << e.part;
                EXPECT_EQ(i.representation, e.representation);
                EXPECT_EQ(i.lodLevel, e.lodLevel);
                EXPECT_EQ(i.clipTime, e.clipTime);
                ASSERT_EQ(i.skinPaletteSize, e.skinPaletteSize);
                for (std::uint32_t j = 0; j < e.skinPaletteSize; ++j) EXPECT_EQ(i.skinPalette[j], e.skinPalette[j]);
                impostorItems += e.representation == Representation::Impostor;
            }
            // Table 2 and the work, summed over the processes, as one process counts them.
            EXPECT_EQ(sum.actorsInScene, one.actorsInScene);
            EXPECT_EQ(sum.actorsAbsent, 0u);
            EXPECT_EQ(sum.a, one.a);
            EXPECT_EQ(sum.b, one.b);
            EXPECT_EQ(sum.c1, one.c1);
            EXPECT_EQ(sum.c2, one.c2);
            EXPECT_EQ(sum.c3_1, one.c3_1);
            EXPECT_EQ(sum.c3_2, one.c3_2);
            EXPECT_EQ(sum.impostors, one.impostors);
            EXPECT_EQ(sum.occludedRefpoint, one.occludedRefpoint);
            EXPECT_EQ(sum.occludedSklsroot, one.occludedSklsroot);
            EXPECT_EQ(sum.culledWithGroup + sum.occludedWithGroup, one.culledWithGroup + one.occludedWithGroup);
            EXPECT_EQ(sum.actorsPosed, one.actorsPosed);
            EXPECT_EQ(sum.skeletonNodesEvaluated, one.skeletonNodesEvaluated);
            occluded += one.occludedRefpoint + one.occludedSklsroot;
        }
        EXPECT_GT(impostorItems, 100u) << "the frames cover impostors";
        EXPECT_GT(occluded, 10u) << "the frames cover occlusion";
    }
}
