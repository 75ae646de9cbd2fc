// Occlusion culling is conservative: from hundreds of cameras in the town (street level, rooftops,
// inside buildings' bounding boxes, grazing walls), an ID render with full depth (every actor posed
// and skinned at full detail, the town drawn as it is drawn, each actor and each tile in its own
// flat colour) shows which actors and tiles have at least one visible pixel; actor processing with
// occlusion must reject none of them. The test also reports how much occlusion rejected, so that a
// buffer that hides nothing cannot pass for a conservative one unnoticed.

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>
#include <random>
#include <set>

#include "throng/testkit/Cameras.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/GlRenderer.h"
#include "throng/scenegraph/Camera.h"
#include "throng/sim/SceneParser.h"
#include "throng/sim/Simulation.h"

namespace throng {
namespace {

constexpr int kWidth = 480, kHeight = 270;
constexpr std::uint32_t kTileBit = 1u << 17;  // IDs of tiles; actors are id + 1 below it

// Six bits of the ID per channel, at the middle of a step of 4 levels: the GL's float to 8-bit
// conversion may round either way by a level and the ID still reads back.
glm::vec4 idColour(std::uint32_t id) {
    const auto level = [&](int shift) { return float(4 * ((id >> shift) & 0x3F) + 2) / 255.0f; };
    return glm::vec4(level(0), level(6), level(12), 1.0f);
}

std::uint32_t idOf(const std::uint8_t* p) { return (p[0] / 4u) | ((p[1] / 4u) << 6) | ((p[2] / 4u) << 12); }

struct Shot {
    const char* kind;
    Camera camera;
};

class OcclusionOracle : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        world_ = sim::Simulation::build(sim::parseSceneFile(THRONG_OCCLUSION_SCENE)).release();
        for (int i = 0; i < 30; ++i) world_->step();  // walkers spread from their start
    }
    static void TearDownTestSuite() {
        delete world_;
        world_ = nullptr;
    }
    static sim::Simulation* world_;
};
sim::Simulation* OcclusionOracle::world_ = nullptr;

Camera camera(const Vec3& eye, const Vec3& target) {
    return testkit::lookingAt(eye, target, {glm::radians(60.0), double(kWidth) / kHeight, 0.2, 800.0});
}

// Cameras of the four kinds the conservative test must survive.
std::vector<Shot> shots(const sim::TownLayout& town) {
    std::mt19937 rng(4242);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<const sim::TilePlacement*> open, buildings;
    for (const auto& t : town.tiles) (sim::tileWalkable(t.kind) ? open : buildings).push_back(&t);
    const double half = 0.5 * town.tileSize;
    const auto pick = [&](const std::vector<const sim::TilePlacement*>& from) { return from[std::size_t(u(rng) * from.size()) % from.size()]; };
    const auto around = [&](const sim::TilePlacement* t, double spread) {
        return town.centre(t->x, t->z) + Vec3((2.0 * u(rng) - 1.0) * spread, 0.0, (2.0 * u(rng) - 1.0) * spread);
    };
    const auto heading = [&](double pitch) {
        const double yaw = 2.0 * 3.14159265358979 * u(rng);
        return Vec3(std::cos(yaw) * std::cos(pitch), std::sin(pitch), std::sin(yaw) * std::cos(pitch));
    };
    std::vector<Shot> out;
    for (int i = 0; i < 80; ++i) {  // street level, looking about
        const Vec3 eye = around(pick(open), half) + Vec3(0.0, 1.5 + 0.5 * u(rng), 0.0);
        out.push_back({"street", camera(eye, eye + heading(0.2 * (u(rng) - 0.5)))});
    }
    for (int i = 0; i < 50; ++i) {  // rooftops, looking down into the streets
        const Vec3 eye = around(pick(buildings), half) + Vec3(0.0, 10.0 + 20.0 * u(rng), 0.0);
        out.push_back({"rooftop", camera(eye, eye + heading(-0.2 - 0.6 * u(rng)))});
    }
    for (int i = 0; i < 40; ++i) {  // inside a building's bounding box
        const Vec3 eye = around(pick(buildings), 0.95 * half) + Vec3(0.0, 0.5 + 8.0 * u(rng), 0.0);
        out.push_back({"inside", camera(eye, eye + heading(0.6 * (u(rng) - 0.5)))});
    }
    for (int i = 0; i < 40; ++i) {  // along a wall: beside a building's side, looking along it
        const sim::TilePlacement* b = pick(buildings);
        const int side = int(4.0 * u(rng)) % 4;
        const Vec3 c = town.centre(b->x, b->z);
        const double offset = half + 0.05 + 0.8 * u(rng), along = (2.0 * u(rng) - 1.0) * half;
        const Vec3 normal = side == 0 ? Vec3(1, 0, 0) : side == 1 ? Vec3(-1, 0, 0) : side == 2 ? Vec3(0, 0, 1) : Vec3(0, 0, -1);
        const Vec3 tangent(normal.z, 0.0, -normal.x);
        const Vec3 eye = c + offset * normal + along * tangent + Vec3(0.0, 1.0 + 3.0 * u(rng), 0.0);
        const double sign = u(rng) < 0.5 ? -1.0 : 1.0;
        out.push_back({"wall", camera(eye, eye + sign * tangent + Vec3(0.0, 0.1 * (u(rng) - 0.5), 0.0) + 0.05 * normal * (u(rng) - 0.5))});
    }
    return out;
}

TEST_F(OcclusionOracle, NoActorOrTileWithAVisiblePixelIsRejected) {
    ASSERT_NE(world_->town(), nullptr);
    ASSERT_TRUE(world_->description().representation.occlusion.has_value());
    auto context = createContext({.width = kWidth, .height = kHeight, .window = false});
    RendererOptions options;
    options.flatTint = true;
    options.clearColor = glm::vec4(0.0f);
    GlRenderer renderer(context, options);

    // Full depth: traditional processing, everything posed, the finest level of every LOD.
    ActorProcessor full(world_->crowd());
    full.setProcessing(Processing::Traditional);
    full.setLodScale(1e-6);
    ActorProcessor occluding(world_->crowd());
    occluding.setOcclusion(world_->description().representation.occlusion);

    const std::vector<Shot> all = shots(*world_->town());
    ASSERT_GE(all.size(), 200u);
    std::map<std::string, std::array<std::uint64_t, 4>> totals;  // visible actors, rejected by occlusion, tiles, tiles rejected
    const double time = world_->now().time;
    for (std::size_t n = 0; n < all.size(); ++n) {
        const Shot& shot = all[n];
        SCOPED_TRACE(std::string(shot.kind) + " camera " + std::to_string(n));
        full.processFrame(world_->root(), shot.camera, time);
        std::map<const Node*, std::uint32_t> tileIds;
        DrawList ids;
        for (const DrawItem& item : full.drawList().items()) {
            DrawItem tinted = item;
            if (item.actor != kNoActor) {
                tinted.tint = idColour(item.actor + 1);
            } else {
                const auto [it, added] = tileIds.emplace(item.node, std::uint32_t(tileIds.size()));
                tinted.tint = idColour(kTileBit | it->second);
            }
            ids.add(tinted, 0);
        }
        renderer.beginFrame(shot.camera);
        renderer.draw(ids);
        const Image image = renderer.readFrame();
        renderer.endFrame();
        std::set<std::uint32_t> seenActors, seenTiles;
        std::size_t unknown = 0;
        std::uint32_t firstUnknown = 0;
        for (std::size_t p = 0; p < image.rgba.size(); p += 4) {
            if (image.rgba[p] == 0 && image.rgba[p + 1] == 0 && image.rgba[p + 2] == 0) continue;  // the clear colour
            const std::uint32_t id = idOf(&image.rgba[p]);
            const bool tile = (id & kTileBit) != 0;
            if ((tile && (id & ~kTileBit) >= tileIds.size()) || (!tile && id - 1 >= world_->crowd().size())) {
                if (unknown++ == 0) firstUnknown = id;  // not an ID the render was given
                continue;
            }
            if (tile) seenTiles.insert(id & ~kTileBit);
            else seenActors.insert(id - 1);
        }
        ASSERT_EQ(unknown, 0u) << "pixels of no ID drawn, the first 0x" << std::hex << firstUnknown;

        const ActorFrameStatistics& s = occluding.processFrame(world_->root(), shot.camera, time);
        std::set<const Node*> drawnTiles;
        for (const DrawItem& item : occluding.drawList().items())
            if (item.actor == kNoActor) drawnTiles.insert(item.node);
        const Crowd::State& state = world_->crowd().state();
        auto& t = totals[shot.kind];
        t[0] += seenActors.size();
        t[1] += s.occludedWithGroup + s.occludedRefpoint + s.occludedSklsroot;
        for (std::uint32_t a : seenActors)
            EXPECT_NE(state.actorClass[a], ActorClass::Occluded) << "actor " << a << " has visible pixels but was rejected as hidden";
        for (const auto& [node, id] : tileIds) {
            if (!seenTiles.count(id)) continue;
            ++t[2];
            if (!drawnTiles.count(node)) {
                ADD_FAILURE() << "tile node '" << node->name() << "' has visible pixels but was not drawn";
                ++t[3];
            }
        }
        if (::testing::Test::HasFailure()) break;
    }
    std::uint64_t rejected = 0;
    for (const auto& [kind, t] : totals) {
        std::cout << "[ occlusion ] " << kind << ": " << t[0] << " visible actors, none rejected; occlusion rejected " << t[1]
                  << " actors in all; " << t[2] << " visible tiles, " << t[3] << " of them not drawn\n";
        rejected += t[1];
    }
    EXPECT_GT(totals["street"][1], 0u) << "occlusion hid nothing from street level: the test proves nothing";
    EXPECT_GT(rejected, 1000u);
}

}  // namespace
}  // namespace throng
