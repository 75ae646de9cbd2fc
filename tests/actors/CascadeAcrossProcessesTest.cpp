// The cascade split over processes that each pose their own actors (Behaviour::presence: the
// others are absent there), each sending its draw items as records (DrawRecords.h): merged in the
// drawing process, the list is item for item the one a process holding every actor makes, frame
// after frame (impostor hysteresis, occlusion against the drawing process's buffer and key-pose
// caches settled over every process included), and the Table-2 counts add up to its.

#include <gtest/gtest.h>

#include <algorithm>
#include <barrier>
#include <cmath>
#include <memory>
#include <random>
#include <thread>
#include <vector>

#include "throng/actors/ActorDrawReferences.h"
#include "throng/actors/ActorGroup.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/KeyPoseArbiter.h"
#include "throng/actors/KeyPoseCache.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/scenegraph/ByteStream.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/DrawRecords.h"
#include "throng/scenegraph/Geometry.h"
#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/Occluder.h"
#include "throng/testkit/ActorTestScenes.h"
#include "throng/testkit/CachedBars.h"
#include "throng/testkit/TownSpread.h"

using namespace throng;

namespace {

using OwnWalkers = testkit::KeyframeShare;

// Compares `merged` with `expected` item by item; numbers drawables, nodes and key-pose sources
// by `mergedRefs` and `expectedRefs` (each process has its own). Returns the items compared.
void expectSameList(const DrawList& merged, const DrawReferences& mergedRefs, const DrawList& expected, const DrawReferences& expectedRefs) {
    ASSERT_EQ(merged.size(), expected.size());
    EXPECT_EQ(merged.primitiveCount(), expected.primitiveCount());
    auto m = merged.items().begin();
    for (const DrawItem& e : expected.items()) {
        const DrawItem& i = *m++;
        ASSERT_EQ(i.actor, e.actor);
        ASSERT_EQ(i.part, e.part);
        EXPECT_EQ(mergedRefs.numberOf(i.drawable), expectedRefs.numberOf(e.drawable));
        EXPECT_EQ(mergedRefs.numberOf(i.node), expectedRefs.numberOf(e.node));
        EXPECT_TRUE(i.world == e.world) << "actor " << e.actor << " part " << e.part;
        EXPECT_EQ(i.representation, e.representation) << "actor " << e.actor;
        EXPECT_EQ(i.lodLevel, e.lodLevel);
        EXPECT_EQ(i.clipTime, e.clipTime);
        ASSERT_EQ(i.skinPaletteSize, e.skinPaletteSize);
        for (std::uint32_t j = 0; j < e.skinPaletteSize; ++j) EXPECT_EQ(i.skinPalette[j], e.skinPalette[j]);
        if (e.representation != Representation::KeyPose) continue;
        EXPECT_EQ(mergedRefs.numberOf(i.keyPose.source), expectedRefs.numberOf(e.keyPose.source));
        for (int k = 0; k < 2; ++k) {
            EXPECT_EQ(i.keyPose.pose[k], e.keyPose.pose[k]);
            EXPECT_EQ(i.keyPose.row[k], e.keyPose.row[k]) << "actor " << e.actor;
        }
        EXPECT_EQ(i.keyPose.blend, e.keyPose.blend);
    }
}

// One process's copy of the scene: a street and a wall (the drawing process only: the others test
// against the occlusion buffer it sends), then two groups of walkers with roaming bounds, as every
// process builds them.
struct World {
    Crowd crowd;
    std::shared_ptr<OwnWalkers> walkers = std::make_shared<OwnWalkers>();
    std::shared_ptr<Group> root = std::make_shared<Group>();
    std::unique_ptr<ActorProcessor> processor;
    DrawReferences refs;
    OcclusionBuffer occlusion{OcclusionSettings{}.width, OcclusionSettings{}.height};
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
        w->root->addChild(std::make_shared<Occluder>(std::vector<AxisBox>{AxisBox{glm::vec3(-30, 0, -1), glm::vec3(30, 12, 1)}},
                                                     AxisBox{glm::vec3(-31, -1, -2), glm::vec3(31, 13, 2)}));
    }
    std::mt19937_64 rng(7);
    std::vector<ActorId> ids[2];
    std::size_t i = 0;
    for (const KeyframeBehaviour::Actor& a : testkit::circleWalkers(humanoid, std::max(humanoid->findClip("walk"), 0), kWalkers, kExtent, rng))
        ids[i++ % 2].push_back(w->crowd.add(humanoid, w->walkers, w->walkers->addActor(a)));
    for (auto& members : ids) {
        auto group = w->crowd.makeGroupNode(members);
        group->setRoamingBound(BoundingSphere(Vec3(0.0), kExtent));
        w->root->addChild(group);
    }
    w->processor = std::make_unique<ActorProcessor>(w->crowd);
    w->processor->setImpostor(*humanoid, impostor());
    w->processor->setImpostorDistance(45.0, 4.0);
    if (draws) w->processor->setOcclusion(OcclusionSettings{});
    else w->processor->setSharedOcclusionBuffer(&w->occlusion);  // the drawing process's, received
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
        // Process p holds the walkers standing in stripe p of the ground (x) at the frame's time,
        // whatever group they are in: walkers crossing a stripe's border change hands (as between
        // ranks), their tiers handed with them.
        std::vector<int> owner(kWalkers, -1);
        std::size_t handedOver = 0, handedAsImpostors = 0;
        // The stripes are the walkers' regions, in every process and the whole world alike.
        auto share = [&](double time) {
            for (auto& part : parts) part->walkers->here.assign(kWalkers, 0);
            whole->walkers->region.assign(kWalkers, 0);
            for (std::size_t i = 0; i < kWalkers; ++i) {
                const double x = whole->walkers->referencePoint(std::uint32_t(i), FrameContext{time, 0.0, 0, nullptr}, nullptr)[3].x;
                const int stripe = std::clamp(int((x / kExtent + 0.5) * processes), 0, processes - 1);
                parts[std::size_t(stripe)]->walkers->here[i] = 1;
                whole->walkers->region[i] = std::uint32_t(stripe);
                if (owner[i] >= 0 && owner[i] != stripe) {
                    const auto tiers = parts[std::size_t(owner[i])]->processor->tiersOf(ActorId(i));
                    parts[std::size_t(stripe)]->processor->setTiers(ActorId(i), tiers);
                    ++handedOver, handedAsImpostors += tiers.impostor;
                }
                owner[i] = stripe;
            }
            for (auto& part : parts) part->walkers->region = whole->walkers->region;
        };
        DrawRecordMerger merger;
        std::uint64_t impostorItems = 0, occluded = 0, cellsHidden = 0;
        for (int f = 0; f < 24; ++f) {
            SCOPED_TRACE("frame " + std::to_string(f));
            const Camera camera = cameraAt(f);
            const double time = 0.8 * f;
            share(time);
            const ActorFrameStatistics one = whole->processor->processFrame(*whole->root, camera, time);
            std::vector<std::vector<std::byte>> bytes(static_cast<std::size_t>(processes));
            ActorFrameStatistics sum;
            std::vector<std::byte> buffer;
            for (int p = 0; p < processes; ++p) {
                World& part = *parts[std::size_t(p)];
                if (p > 0) {  // the drawing process's buffer of this frame, as received
                    ByteReader in(buffer, "occlusion buffer");
                    part.occlusion.read(in);
                }
                const ActorFrameStatistics& s = part.processor->processFrame(*part.root, camera, time);
                writeDrawRecords(part.processor->drawList(), part.refs, bytes[std::size_t(p)]);
                addShare(sum, s);
                if (p == 0) {
                    ByteWriter out(buffer);
                    part.processor->occlusion()->buffer().write(out);
                }
            }
            // The drawing process: its own items of no actor, then everyone's merged.
            DrawList merged;
            for (const DrawItem& item : parts[0]->processor->drawList().items())
                if (item.actor == kNoActor) merged.add(item, item.drawable->primitiveCount());
            std::vector<std::span<const std::byte>> messages(bytes.begin(), bytes.end());
            merger.merge(messages, parts[0]->refs, merged);

            expectSameList(merged, parts[0]->refs, whole->processor->drawList(), whole->refs);
            for (const DrawItem& e : whole->processor->drawList().items()) impostorItems += e.representation == Representation::Impostor;
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
            EXPECT_EQ(sum.occlusionObjectsTested, one.occlusionObjectsTested) << "what occlusion's rest weighs";
            EXPECT_EQ(sum.nodesOccluded, one.nodesOccluded) << "nodes are counted by the process drawing the buffer";
            // Occlusion's cells never span two regions: each process forms one process's cells.
            EXPECT_EQ(sum.occlusionTests, one.occlusionTests);
            EXPECT_EQ(sum.occlusionCellsTested, one.occlusionCellsTested);
            EXPECT_EQ(sum.occlusionCellsHidden, one.occlusionCellsHidden);
            cellsHidden += one.occlusionCellsHidden;
            EXPECT_EQ(sum.culledWithGroup + sum.occludedWithGroup, one.culledWithGroup + one.occludedWithGroup);
            EXPECT_EQ(sum.actorsPosed, one.actorsPosed);
            EXPECT_EQ(sum.skeletonNodesEvaluated, one.skeletonNodesEvaluated);
            occluded += one.occludedRefpoint + one.occludedSklsroot;
        }
        EXPECT_GT(impostorItems, 100u) << "the frames cover impostors";
        EXPECT_GT(handedAsImpostors, 3u) << "the frames cover walkers handed over as impostors (" << handedOver << " handed over)";
        EXPECT_GT(occluded, 10u) << "the frames cover occlusion";
        EXPECT_GT(cellsHidden, 0u) << "the frames cover occlusion's cells";
    }
}

namespace {

// Processes on threads of one program settling their key-pose caches together: every process
// brings its demands, process 0 selects for their sum and the others copy its rows (what ranks do
// over messages).
class SharedSelection {
public:
    explicit SharedSelection(int processes) : barrier_(processes), demands_(std::size_t(processes)) {}

    // Process `index`'s arbiter.
    class Member : public KeyPoseArbiter {
    public:
        Member(SharedSelection& shared, int index) : shared_(shared), index_(std::size_t(index)) {}
        KeyPoseSelectionCounts settle(std::span<const std::vector<KeyPoseDemand>> demands,
                                      std::span<const std::shared_ptr<KeyPoseCache>> caches, std::uint64_t frame) override {
            SharedSelection& s = shared_;
            s.demands_[index_].assign(demands.begin(), demands.end());
            s.barrier_.arrive_and_wait();
            KeyPoseSelectionCounts counts;
            if (index_ == 0) {
                s.rows_.assign(caches.size(), {});
                for (std::size_t ci = 0; ci < caches.size(); ++ci) {
                    std::vector<KeyPoseDemand> sum;
                    for (const auto& part : s.demands_) addKeyPoseDemands(sum, part[ci]);
                    const KeyPoseSelectionCounts c = s.selector_.select(*caches[ci], sum, frame);
                    counts.wanted += c.wanted, counts.updates += c.updates, counts.held += c.held;
                    const auto poses = caches[ci]->rows().rowPoses();
                    s.rows_[ci].assign(poses.begin(), poses.end());
                }
            }
            s.barrier_.arrive_and_wait();
            if (index_ != 0)
                for (std::size_t ci = 0; ci < caches.size(); ++ci) caches[ci]->rows().copyRows(s.rows_[ci]);
            return counts;
        }

    private:
        SharedSelection& shared_;
        std::size_t index_;
    };

private:
    std::barrier<> barrier_;
    std::vector<std::vector<std::vector<KeyPoseDemand>>> demands_;  // per process, per cache
    std::vector<std::vector<std::uint32_t>> rows_;                    // per cache: process 0's rows
    KeyPoseSelector selector_;
};

using Bars = testkit::CachedBars;

std::unique_ptr<Bars> bars(KeyPoseMode mode, std::uint32_t rows) { return testkit::cachedBars(240, rows, mode); }

}  // namespace

// Key-pose caches too small for every pose wanted: settled over the demands of every process,
// each process draws from the rows one process would hold, and misses the same actors.
TEST(CascadeAcrossProcesses, KeyPoseCachesSettledOverEveryProcessHoldWhatOneProcessHolds) {
    for (const KeyPoseMode mode : {KeyPoseMode::Intermittent, KeyPoseMode::Interpolative}) {
        SCOPED_TRACE(mode == KeyPoseMode::Intermittent ? "intermittent" : "interpolative");
        constexpr int kProcesses = 3;
        auto whole = bars(mode, 6);
        std::vector<std::unique_ptr<Bars>> parts;
        SharedSelection shared(kProcesses);
        std::vector<std::unique_ptr<SharedSelection::Member>> arbiters;
        for (int p = 0; p < kProcesses; ++p) {
            parts.push_back(bars(mode, 6));
            parts.back()->behaviour->here.assign(240, 0);
            for (std::size_t i = 0; i < 240; ++i) parts.back()->behaviour->here[i] = i % kProcesses == std::size_t(p);
            arbiters.push_back(std::make_unique<SharedSelection::Member>(shared, p));
            parts.back()->processor->setKeyPoseArbiter(arbiters.back().get());
        }
        Camera camera;
        camera.setPerspective(1.2, 1.0, 0.1, 1000.0);
        DrawRecordMerger merger;
        std::uint64_t cached = 0, missed = 0;
        for (int f = 0; f < 12; ++f) {
            SCOPED_TRACE("frame " + std::to_string(f));
            camera.setLookAt(Vec3(0.3 * f, 1.0, -2.0 + 0.8 * f), Vec3(0.3 * f, 1.0, 30.0));
            const double time = 0.13 * f;
            const ActorFrameStatistics one = whole->processor->processFrame(*whole->root, camera, time);
            std::vector<std::vector<std::byte>> bytes(kProcesses);
            std::vector<ActorFrameStatistics> shares(kProcesses);
            {
                std::vector<std::jthread> threads;
                for (int p = 0; p < kProcesses; ++p)
                    threads.emplace_back([&, p] {
                        Bars& part = *parts[std::size_t(p)];
                        shares[std::size_t(p)] = part.processor->processFrame(*part.root, camera, time);
                        writeDrawRecords(part.processor->drawList(), part.refs, bytes[std::size_t(p)]);
                    });
            }
            DrawList merged;
            std::vector<std::span<const std::byte>> messages(bytes.begin(), bytes.end());
            merger.merge(messages, parts[0]->refs, merged);
            expectSameList(merged, parts[0]->refs, whole->processor->drawList(), whole->refs);
            ActorFrameStatistics sum;
            for (const ActorFrameStatistics& s : shares) addShare(sum, s);
            EXPECT_EQ(sum.keyPoseBand, one.keyPoseBand);
            EXPECT_EQ(sum.keyPoseActors, one.keyPoseActors);
            EXPECT_EQ(sum.keyPoseMisses, one.keyPoseMisses);
            EXPECT_EQ(shares[0].keyPosesWanted, one.keyPosesWanted);
            EXPECT_EQ(shares[0].keyPoseUpdates, one.keyPoseUpdates);
            EXPECT_EQ(shares[0].keyPosesHeld, one.keyPosesHeld);
            EXPECT_EQ(sum.actorsPosed, one.actorsPosed);
            cached += one.keyPoseActors, missed += one.keyPoseMisses;
        }
        EXPECT_GT(cached, 100u) << "the frames cover actors drawn from the cache";
        EXPECT_GT(missed, 20u) << "the frames cover actors whose poses did not fit";
    }
}

// An actor's tiers read back as the frame left them and as set; an actor or a tier that cannot be
// is refused.
TEST(CascadeAcrossProcesses, TiersReadBackAndBadOnesAreRefused) {
    auto w = world(false);
    Camera camera = cameraAt(0);
    w->processor->processFrame(*w->root, camera, 0.0);
    std::size_t impostors = 0;
    for (ActorId id = 0; id < kWalkers; ++id) {
        EXPECT_EQ(w->processor->tiersOf(id).impostor, w->processor->drawnAsImpostor(id) ? 1 : 0) << "actor " << id;
        impostors += w->processor->drawnAsImpostor(id);
    }
    EXPECT_GT(impostors, 0u);
    w->processor->setTiers(3, {1, 0});
    EXPECT_EQ(w->processor->tiersOf(3), (ActorProcessor::ActorTiers{1, 0}));
    EXPECT_THROW(w->processor->setTiers(ActorId(kWalkers), {}), std::invalid_argument);
    EXPECT_THROW(w->processor->setTiers(0, {2, 0}), std::invalid_argument);
    EXPECT_EQ(w->processor->tiersOf(ActorId(kWalkers + 5)), ActorProcessor::ActorTiers{}) << "beyond the crowd: none";
}
