// A warm frame allocates nothing and faults nothing. For actor and traditional processing, on the
// Table-2 scene and on a town-like spread of 10,000 actors (rigid humanoids, and skinned CesiumMan
// for key-pose caches), with and without impostors and key-pose caches: 60 frames are run twice to
// warm up, then the same 60 frames again while every heap allocation of the process is counted
// (AllocationCounter) and the kernel's minor page faults are read. Nothing is timed.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "AllocationCounter.h"
#include "throng/testkit/Assets.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/research/CostModelScene.h"
#include "throng/actors/KeyPoseCache.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/actors/Table3Template.h"
#include "throng/gltf/GltfLoader.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/MeshShapes.h"
#include "throng/testkit/TownSpread.h"

using namespace throng;
using namespace throng::testkit;

namespace {

constexpr int kFrames = 60;
constexpr std::size_t kActors = 10000;
// A page or two may still be mapped in by the kernel's own bookkeeping (a stack page, a timer);
// a frame that touched fresh storage would fault hundreds.
constexpr double kFaultsPerFrame = 0.5;

enum class Layout { Table2, Town, SkinnedTown };

struct Case {
    Layout layout;
    Processing processing;
    bool impostors = false;  ///< actor processing: far actors drawn as one impostor item
    bool keyPoses = false;   ///< actor processing: middle actors drawn from a key-pose cache
    unsigned threads = 1;
    std::string name;
};

// Names a case in gtest's messages.
[[maybe_unused]] void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

struct Scene {
    Crowd crowd;
    std::shared_ptr<Group> root;
    Camera camera;
    double time = 0.0;
    std::shared_ptr<const ActorTemplate> tmpl;
};

std::shared_ptr<const ActorTemplate> cesiumMan() {
    return loadCharacter(testkit::sharedAssets() + "/characters/CesiumMan.glb").primaryTemplate();
}

std::unique_ptr<Scene> build(Layout layout) {
    auto s = std::make_unique<Scene>();
    if (layout == Layout::Table2) {
        CostModelSceneOptions options;
        options.counts = CascadeCounts::scaled(kActors);
        options.group = true;
        s->tmpl = makeTable3Template();
        const CostModelScene built = buildCostModelScene(s->crowd, s->tmpl, std::make_shared<KeyframeBehaviour>(), options);
        s->root = built.root;
        s->camera = built.camera;
        s->time = built.time;
        return s;
    }
    s->tmpl = layout == Layout::SkinnedTown ? cesiumMan() : makeSeedHumanoid();
    testkit::TownSpread town = testkit::buildTownSpread(s->crowd, kActors, 40.0 * std::sqrt(double(kActors)), 50.0, 1, s->tmpl);
    s->root = town.root;
    s->camera = town.camera;
    return s;
}

struct Counts {
    std::uint64_t allocations = 0;
    long faults = 0;
};

Counts steadyFrames(const Case& c) {
    const std::unique_ptr<Scene> s = build(c.layout);
    ActorProcessor processor(s->crowd);
    processor.setProcessing(c.processing);
    processor.setThreads(c.threads);
    const auto impostor = std::make_shared<MeshDrawable>(makeBox("impostor", glm::vec3(0, 1, 0), glm::vec3(0.4f, 1.0f, 0.1f)));
    if (c.impostors) {
        processor.setImpostor(*s->tmpl, impostor);
        processor.setImpostorDistance(c.layout == Layout::Table2 ? 150.0 : 60.0, 2.0);
    }
    if (c.keyPoses) {
        KeyPoseCacheSettings settings;
        settings.rows = 48;
        processor.setKeyPoseCache(std::make_shared<KeyPoseCache>(s->tmpl, settings));
        processor.setKeyPoseDistance(20.0, 1.0);
    }
    auto frames = [&] {
        for (int k = 0; k < kFrames; ++k) processor.processFrame(*s->root, s->camera, s->time + double(k) / 30.0);
    };
    // Warm: every list and workspace has seen these frames' sizes. Twice, because storage a list
    // outgrew in its last frames of the first pass is merged into one block when it is next
    // cleared (FrameArena), which is in the second.
    frames();
    frames();
    const std::uint64_t allocations = heapAllocations();
    const long faults = minorPageFaults();
    frames();
    const Counts counts{heapAllocations() - allocations, minorPageFaults() - faults};
    // The frames did real work: something was drawn, and the tiers asked for were used.
    const ActorFrameStatistics& st = processor.statistics();
    EXPECT_GT(st.drawItems, 100u);
    if (c.impostors) {
        EXPECT_GT(st.impostors, 0u);
    }
    if (c.keyPoses) {
        EXPECT_GT(st.keyPoseActors, 0u);
    }
    return counts;
}

class SteadyFrame : public ::testing::TestWithParam<Case> {};

}  // namespace

// The hooks see allocations made by any means, so a zero below means none was made.
TEST(AllocationCounter, CountsEveryWayOfAllocating) {
    if (!allocationsCounted()) GTEST_SKIP() << "AddressSanitizer owns the allocator here";
    // Kept where the optimiser cannot prove them unused (it may drop an allocation nobody reads).
    static void* volatile kept[3];
    const std::uint64_t before = heapAllocations();
    kept[0] = new int(3);
    kept[1] = std::malloc(64);
    auto* many = new std::vector<double>(1000, 1.0);
    kept[2] = many;
    const std::uint64_t after = heapAllocations();
    EXPECT_EQ(after - before, 4u);  // the int, the raw block, the vector and its elements
    delete many;
    std::free(kept[1]);
    delete static_cast<int*>(kept[0]);
}

TEST_P(SteadyFrame, AllocatesNothingAndFaultsAlmostNothing) {
    if (!allocationsCounted()) GTEST_SKIP() << "AddressSanitizer owns the allocator here";
    const Counts counts = steadyFrames(GetParam());
    EXPECT_EQ(counts.allocations, 0u) << "heap allocations in " << kFrames << " warm frames";
    EXPECT_LE(double(counts.faults) / kFrames, kFaultsPerFrame) << counts.faults << " minor page faults in " << kFrames
                                                                << " warm frames";
}

INSTANTIATE_TEST_SUITE_P(
    Frames, SteadyFrame,
    ::testing::Values(Case{Layout::Table2, Processing::Traditional, false, false, 1, "Table2Traditional"},
                      Case{Layout::Table2, Processing::Actor, false, false, 1, "Table2Actor"},
                      Case{Layout::Table2, Processing::Actor, true, false, 1, "Table2ActorImpostors"},
                      Case{Layout::Town, Processing::Traditional, false, false, 1, "TownTraditional"},
                      Case{Layout::Town, Processing::Actor, false, false, 1, "TownActor"},
                      Case{Layout::Town, Processing::Actor, true, false, 1, "TownActorImpostors"},
                      Case{Layout::Town, Processing::Actor, true, false, 2, "TownActorImpostorsTwoThreads"},
                      Case{Layout::SkinnedTown, Processing::Traditional, false, false, 1, "SkinnedTownTraditional"},
                      Case{Layout::SkinnedTown, Processing::Actor, true, true, 1, "SkinnedTownActorImpostorsKeyPoses"}),
    [](const ::testing::TestParamInfo<Case>& param) { return param.param.name; });
