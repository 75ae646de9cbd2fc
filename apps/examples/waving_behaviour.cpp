// A custom behaviour with two levels of detail: an audience that waves. Near the camera (level 0)
// each actor waves its right arm from the shoulder and the elbow and nods; farther (level 1) only
// the shoulder swings, one sine instead of three; beyond the last band the actor keeps its rest
// pose. The cascade picks the level from each actor's eye distance; the program prints how many
// Skeleton nodes it evaluated for a near and a far camera.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <exception>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include <throng/actors/ActorGroup.h>
#include <throng/actors/ActorProcessor.h>
#include <throng/actors/ActorTemplate.h>
#include <throng/actors/Behaviour.h>
#include <throng/actors/Crowd.h>
#include <throng/actors/SeedHumanoid.h>
#include <throng/actors/SkeletonPose.h>
#include <throng/scenegraph/Camera.h>
#include <throng/scenegraph/Group.h>

// One behaviour object drives many actors, each in its own slot; it may be called from several
// threads at once for different slots, so it touches only that slot's state.
class Waving : public throng::Behaviour {
public:
    explicit Waving(const throng::ActorTemplate& tmpl)
        : shoulder_(tmpl.dofValueOffset(std::size_t(tmpl.findNode("rShoulder")), 1)),
          elbow_(tmpl.dofValueOffset(std::size_t(tmpl.findNode("rElbow")), 0)),
          neck_(tmpl.dofValueOffset(std::size_t(tmpl.findNode("neck")), 0)) {}

    // An actor stands at `position`, facing `heading`, waving with its own phase.
    std::uint32_t addActor(throng::Vec3 position, double heading, double phase) {
        seats_.push_back({position, heading, phase});
        return std::uint32_t(seats_.size() - 1);
    }

    // Level 0 within 15 m (scaled eye distance), level 1 within 40 m, rest pose beyond.
    std::span<const double> levelEnds() const override { return ends_; }

    // Phase 1: where the actor is, whatever the camera. Standing actors: a fixed matrix.
    throng::Mat4 referencePoint(std::uint32_t slot, const throng::FrameContext&, throng::OpTally*) override {
        const Seat& s = seats_[slot];
        throng::Mat4 m = glm::rotate(throng::Mat4(1.0), s.heading, throng::Vec3(0, 1, 0));
        m[3] = throng::Vec4(s.position, 1.0);
        return m;
    }
    // Phase 3: the Skeleton Root relative to the Reference Point; the figure stands still on it.
    throng::RootPose skeletonRoot(std::uint32_t, double, int, throng::OpTally*) override { return {}; }

    // Phase 5, only for actors that survived CULL 1 and 2, only for their active Skeleton nodes.
    void pose(std::uint32_t slot, double time, int level, const throng::ActorTemplate& tmpl,
              std::span<const std::uint8_t> active, std::span<float> dofs, throng::OpTally*) override {
        throng::writeRestPose(tmpl, active, dofs);  // everything at rest, then the wave on top
        posedAt_[std::min(level, 2)].fetch_add(1, std::memory_order_relaxed);  // for the printout only
        if (level >= 2) return;
        const double t = 2.0 * time + seats_[slot].phase;
        dofs[shoulder_] = float(-1.2 + 0.3 * std::sin(t));  // arm raised (rotation about Z), swinging
        if (level == 0) {                                  // near: the elbow and a nod as well
            dofs[elbow_] = float(-0.8 - 0.4 * std::sin(2.0 * t));
            dofs[neck_] = float(0.1 * std::sin(0.5 * t));
        }
    }

    // The Skeleton Root never leaves the Reference Point: a small sphere round it.
    throng::BoundingSphere skeletonRootExtent(std::uint32_t) const override { return throng::BoundingSphere({}, 0.01); }
    // Poses are not the template's clips: the cascade bounds actors with the template's reach.
    bool posesFromTemplateClips() const override { return false; }
    std::size_t bytesPerSlot() const override { return sizeof(Seat); }

    // Actors posed at level 0, 1 and beyond since the last call (the printout's counters).
    std::array<std::uint64_t, 3> takePosedPerLevel() {
        return {posedAt_[0].exchange(0), posedAt_[1].exchange(0), posedAt_[2].exchange(0)};
    }

private:
    struct Seat {
        throng::Vec3 position;
        double heading, phase;
    };
    std::vector<Seat> seats_;
    const double ends_[2] = {15.0, 40.0};
    std::uint32_t shoulder_, elbow_, neck_;  // where the waved DOFs sit in an actor's DOF values
    std::atomic<std::uint64_t> posedAt_[3] = {};
};

int main() try {
    const auto humanoid = throng::makeSeedHumanoid();
    auto waving = std::make_shared<Waving>(*humanoid);
    throng::Crowd crowd;
    std::vector<throng::ActorId> ids;
    for (int row = 0; row < 20; ++row)  // an audience of 20 rows of 30 seats
        for (int seat = 0; seat < 30; ++seat)
            ids.push_back(crowd.add(humanoid, waving, waving->addActor({1.0 * seat - 15.0, 0.0, 2.0 * row}, 3.1416, 0.1 * seat)));
    auto scene = std::make_shared<throng::Group>();
    scene->addChild(crowd.makeGroupNode(ids));

    throng::ActorProcessor processor(crowd);
    for (double distance : {5.0, 30.0, 60.0}) {  // the camera backs away from the front row
        throng::Camera camera;
        camera.setPerspective(1.2, 16.0 / 9.0, 0.1, 500.0);
        camera.setLookAt(throng::Vec3(0, 1.7, -distance), throng::Vec3(0, 1.0, 10.0), throng::Vec3(0, 1, 0));
        const throng::FrameContext context{1.0, 1.0 / 30.0, 0, nullptr};
        crowd.step(context);
        const throng::ActorFrameStatistics& s = processor.processFrame(*scene, camera, context.time);
        const auto levels = waving->takePosedPerLevel();
        std::printf("camera %2.0f m from the front row: %llu actors posed (level 0: %llu, level 1: %llu, rest pose: %llu), "
                    "%llu Skeleton nodes evaluated\n",
                    distance, (unsigned long long)s.actorsPosed, (unsigned long long)levels[0],
                    (unsigned long long)levels[1], (unsigned long long)levels[2],
                    (unsigned long long)s.skeletonNodesEvaluated);
    }
    return 0;
} catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
}
