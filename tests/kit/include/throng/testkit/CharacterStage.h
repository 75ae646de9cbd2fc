#pragma once
// One loaded character on a stage of its own, and the views and clip times of the character golden
// images. Shared by CharacterRenderTest (which keeps the goldens) and the VTK oracle in
// tests/oracles (which checks them against another implementation), so both see the very same
// frames.

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "throng/actors/Actor.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/render/CpuSkinning.h"
#include "throng/render/GlRenderer.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/MeshDrawable.h"

namespace throng::testkit {

/// One item drawn alone by `renderer` seen by `camera`, and the frame read back: what a test
/// compares when it changes one palette or one matrix by hand.
inline Image drawAlone(GlRenderer& renderer, const Camera& camera, const DrawItem& item) {
    DrawList list;
    list.add(item, item.drawable->primitiveCount());
    renderer.beginFrame(camera);
    renderer.draw(list);
    Image image = renderer.readFrame();
    renderer.endFrame();
    return image;
}

/// One actor of a template playing one clip at the origin, facing +Z, in a scene of its own: its
/// Skeleton Root frame is the world frame.
struct Stage {
    Crowd crowd;                                       ///< holds the one actor
    std::shared_ptr<Group> root = std::make_shared<Group>();  ///< the scene
    ActorId id{};                                      ///< the actor
    ActorProcessor processor{crowd};                   ///< actor processing of the scene

    /// The actor plays clip `clip` of `tmpl`, looped, interpolated at every distance.
    Stage(std::shared_ptr<const ActorTemplate> tmpl, int clip) {
        auto behaviour = std::make_shared<KeyframeBehaviour>();
        KeyframeBehaviour::Actor a;
        a.tmpl = tmpl;
        a.clip = clip;
        id = crowd.add(tmpl, behaviour, behaviour->addActor(a));
        root->addChild(crowd.makeActorNode(id));
        processor.setBehaviouralLod(false);  // always interpolate: the pose depends on time alone
    }

    /// A camera at `time` from `azimuth` (radians about +Y from +Z) and `elevation`, at a distance
    /// set by the Sklsroot sphere's radius (the same framing for a character in centimetres as in
    /// metres), looking at the middle of the posed mesh (the Skeleton Root is often at the feet).
    Camera frame(double time, double azimuth, double elevation) {
        const double r = crowd.skeletonRootRadius(id);
        // First a frame seen from far away, to pose the actor at `time`.
        Camera far;
        far.setPerspective(std::numbers::pi / 4.0, 1.0, 0.01 * r, 200.0 * r);
        far.setLookAt(Vec3(0.0, 0.0, 50.0 * r), Vec3(0.0));
        processor.processFrame(*root, far, time);
        Vec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
        for (const DrawItem& item : processor.drawList().items()) {
            const auto* drawable = dynamic_cast<const MeshDrawable*>(item.drawable);
            if (!drawable) continue;
            const MeshData& mesh = drawable->mesh();
            std::vector<glm::vec3> positions(mesh.positions);
            if (item.skinPalette) skinMesh(mesh, std::span(item.skinPalette, item.skinPaletteSize), positions, {});
            for (const glm::vec3& p : positions) {
                const Vec3 w(item.world.toMat4() * Vec4(Vec3(p), 1.0));
                lo = glm::min(lo, w);
                hi = glm::max(hi, w);
            }
        }
        const Vec3 centre = lo.x <= hi.x ? 0.5 * (lo + hi) : Vec3(crowd.skeletonRoot(id)[3]);
        const double d = 1.6 * r;  // the sphere is conservative (every pose of every clip, plus a margin)
        const Vec3 eye = centre + d * Vec3(std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                                           std::cos(azimuth) * std::cos(elevation));
        Camera camera;
        camera.setPerspective(std::numbers::pi / 4.0, 1.0, 0.02 * d, 10.0 * d);
        camera.setLookAt(eye, centre);
        return camera;
    }

    /// Draws the frame at `time` seen by `camera` and reads it back.
    Image render(GlRenderer& renderer, const Camera& camera, double time) {
        processor.processFrame(*root, camera, time, &renderer);
        return renderer.readFrame();
    }
};

/// Side of the square character frames, pixels.
constexpr int kCharacterFrameSize = 160;

/// A golden image of a loaded character: which file, clip, time and view.
struct CharacterGoldenCase {
    const char* golden;   ///< golden/<golden>.png
    const char* file;     ///< characters/<file> in the shared assets
    const char* clip;     ///< clip name ("" for the first)
    double time;          ///< seconds into the clip
    double azimuthDeg;    ///< camera direction about +Y, from +Z (the characters' front)
    double elevationDeg;  ///< camera height angle
};

/// The character golden images (tests/render/golden/character_*.png).
inline constexpr CharacterGoldenCase kCharacterGoldenCases[] = {
    {"character_cesium_man_front", "CesiumMan.glb", "", 0.40, 30.0, 10.0},
    {"character_cesium_man_side", "CesiumMan.glb", "", 1.10, 90.0, 0.0},
    {"character_fox_walk_front", "Fox.glb", "Walk", 0.25, 35.0, 15.0},
    {"character_fox_walk_side", "Fox.glb", "Walk", 0.55, -90.0, 5.0},
    {"character_robot_walk_front", "robot.glb", "Robot_Walking", 0.30, 25.0, 10.0},
    {"character_robot_walk_back", "robot.glb", "Robot_Walking", 0.85, 160.0, 20.0},
};

}  // namespace throng::testkit
