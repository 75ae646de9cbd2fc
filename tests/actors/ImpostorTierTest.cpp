// Hybrid LOD: beyond the impostor distance an actor is one impostor item and none of its Skeleton
// nodes is processed; switching has hysteresis; the default (distance 0) changes nothing.

#include <gtest/gtest.h>

#include <memory>

#include "throng/actors/Actor.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/MeshShapes.h"

namespace throng {
namespace {

struct OneActor {
    Crowd crowd;
    std::shared_ptr<const ActorTemplate> tmpl = makeSeedHumanoid();
    std::shared_ptr<Group> root = std::make_shared<Group>();
    std::shared_ptr<const Drawable> impostor =
        std::make_shared<MeshDrawable>(makeBox("impostor stand-in", glm::vec3(0, 1, 0), glm::vec3(0.5f, 1.0f, 0.1f)));
    ActorId id = 0;

    OneActor() {
        auto behaviour = std::make_shared<KeyframeBehaviour>();
        KeyframeBehaviour::Actor a;
        a.tmpl = tmpl;
        id = crowd.add(tmpl, behaviour, behaviour->addActor(a));
        root->addChild(crowd.makeActorNode(id));
    }
    // Processes a frame with the eye `distance` metres away along +Z.
    const ActorFrameStatistics& frame(ActorProcessor& p, double distance) {
        Camera camera;
        camera.setLookAt(Vec3(0, 1, distance), Vec3(0, 1, 0));
        return p.processFrame(*root, camera, 0.5);
    }
};

TEST(ImpostorTier, OffByDefault) {
    OneActor s;
    ActorProcessor p(s.crowd);
    p.setImpostor(*s.tmpl, s.impostor);
    EXPECT_EQ(p.impostorDistance(), 0.0);
    const ActorFrameStatistics& st = s.frame(p, 500.0);
    EXPECT_EQ(st.impostors, 0u);
    EXPECT_FALSE(p.drawnAsImpostor(s.id));
}

TEST(ImpostorTier, FarActorsAreImpostorsWithHysteresis) {
    OneActor s;
    ActorProcessor p(s.crowd);
    p.setImpostorDistance(50.0, 5.0);
    p.setImpostor(*s.tmpl, s.impostor);
    struct Step {
        double distance;
        bool impostor;
    };
    // In from far, back out: the tier changes only past 45 m going in and 55 m going out.
    for (const Step& step : {Step{100, true}, Step{52, true}, Step{46, true}, Step{44, false}, Step{50, false},
                             Step{54, false}, Step{56, true}, Step{50, true}}) {
        const ActorFrameStatistics& st = s.frame(p, step.distance);
        EXPECT_EQ(p.drawnAsImpostor(s.id), step.impostor) << "at " << step.distance << " m";
        if (step.impostor) {
            EXPECT_EQ(st.impostors, 1u);
            EXPECT_EQ(st.skeletonNodesEvaluated, 0u) << "an impostor processes no Skeleton node";
            EXPECT_EQ(st.actorsPosed, 0u);
            ASSERT_EQ(p.drawList().size(), 1u);
            EXPECT_EQ(p.drawList().items()[0].drawable, s.impostor.get());
        } else {
            EXPECT_EQ(st.impostors, 0u);
            EXPECT_GT(st.skeletonNodesEvaluated, 0u);
        }
    }
}

TEST(ImpostorTier, NoImpostorForTheTemplateKeepsGeometry) {
    OneActor s;
    ActorProcessor p(s.crowd);
    p.setImpostorDistance(10.0);
    EXPECT_EQ(s.frame(p, 100.0).impostors, 0u);
    EXPECT_THROW(p.setImpostorDistance(-1.0), std::invalid_argument);
}

}  // namespace
}  // namespace throng
