#include "throng/actors/ProceduralBird.h"

#include <cmath>
#include <numbers>

#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/MeshShapes.h"

namespace throng {

std::shared_ptr<const ActorTemplate> makeProceduralBird(const ProceduralBirdLods& l) {
    const glm::vec4 feathers(0.35f, 0.33f, 0.3f, 1.0f), belly(0.8f, 0.78f, 0.72f, 1.0f);
    auto mesh = [](std::shared_ptr<MeshData> m) -> std::shared_ptr<const Drawable> { return std::make_shared<MeshDrawable>(std::move(m)); };
    ActorTemplateBuilder b("bird");
    SkeletonNode body;
    body.name = "body";
    body.deactivationDistance = l.far;
    // Near: body and head apart; far: one rounded body with the wings folded in.
    auto torso = makeCapsule("bird_body", glm::vec3(0, 0, 0), 0.09f, 0.12f, 12, 3, belly);
    for (glm::vec3& p : torso->positions) p = glm::vec3(p.x, p.z * 0.6f, p.y - 0.15f);  // lie along +Z
    auto head = makeSphere("bird_head", glm::vec3(0, 0.05f, 0.2f), 0.06f, 10, 6, feathers);
    body.geometry.addLevel(l.near, mesh(mergeMeshes("bird_body_L0", *torso, *head)));
    body.geometry.addLevel(l.far, mesh(makeBox("bird_body_L1", glm::vec3(0, 0, 0.02f), glm::vec3(0.3f, 0.05f, 0.17f), feathers)));
    const int iBody = b.addNode(body);
    for (int side = 0; side < 2; ++side) {
        const float s = side == 0 ? 1.0f : -1.0f;
        SkeletonNode wing;
        wing.name = side == 0 ? "lWing" : "rWing";
        wing.parent = iBody;
        wing.restTranslation = glm::vec3(s * 0.07f, 0.02f, 0.0f);
        wing.dofs = {Dof::rotation(glm::vec3(0, 0, s), -0.9f, 0.9f)};
        wing.deactivationDistance = l.near;
        wing.geometry.addLevel(l.near, mesh(makeBox(wing.name + "_L0", glm::vec3(s * 0.28f, 0, 0), glm::vec3(0.28f, 0.01f, 0.1f), feathers)));
        b.addNode(wing);
    }
    SkeletonNode tail;
    tail.name = "tail";
    tail.parent = iBody;
    tail.restTranslation = glm::vec3(0, 0.0f, -0.22f);
    tail.dofs = {Dof::rotation(glm::vec3(1, 0, 0), -0.5f, 0.5f)};
    tail.deactivationDistance = l.near;
    tail.geometry.addLevel(l.near, mesh(makeBox("tail_L0", glm::vec3(0, 0, -0.08f), glm::vec3(0.06f, 0.01f, 0.08f), feathers)));
    b.addNode(tail);

    // "flap": a 0.4 s wing beat, keys every 0.05 s; the tail trims.
    std::vector<ClipChannel> channels;
    for (std::uint32_t node : {1u, 2u}) {
        ClipChannel c;
        c.node = node;
        for (int k = 0; k <= 8; ++k) {
            c.times.push_back(0.05f * float(k));
            c.values.push_back(0.75f * std::sin(2.0f * std::numbers::pi_v<float> * float(k) / 8.0f));
        }
        channels.push_back(c);
    }
    ClipChannel trim;
    trim.node = 3;
    trim.times = {0.0f, 0.2f, 0.4f};
    trim.values = {0.1f, -0.1f, 0.1f};
    channels.push_back(trim);
    b.addClip(std::make_shared<AnimationClip>("flap", std::move(channels)));
    return b.build();
}

}  // namespace throng
