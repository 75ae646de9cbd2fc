#include "throng/testkit/DrawnJoints.h"

#include "throng/actors/ActorTemplate.h"

namespace throng::testkit {

const std::vector<Vec3>& DrawnJoints::bindPositions(const ActorTemplate& tmpl) {
    auto [it, added] = bind_.try_emplace(&tmpl);
    if (added) {
        // A joint's origin in the bind pose: where its inverse bind matrix sends to the origin.
        for (const SkeletonNode& n : tmpl.nodes()) it->second.push_back(Vec3(glm::inverse(glm::dmat4(n.inverseBind))[3]));
    }
    return it->second;
}

void DrawnJoints::collect(const DrawList& list, const Crowd& crowd) {
    byActor_.clear();
    const Crowd::State& s = crowd.state();
    for (const DrawItem& item : list.items()) {
        if (item.actor == kNoActor || item.actor >= crowd.size()) continue;
        const ActorTemplate& t = *s.tmpl[item.actor];
        const std::vector<Vec3>& bind = bindPositions(t);
        const Mat4 world = item.world.toMat4();
        auto place = [&](Joints& j, const Skin& skin, std::span<const glm::mat4> palette, std::span<const glm::mat4> second, float blend) {
            for (std::size_t k = 0; k < skin.joints.size() && k < palette.size(); ++k) {
                const std::uint32_t n = skin.joints[k];
                const Vec4 b(bind[n], 1.0);
                Vec4 model = glm::dmat4(palette[k]) * b;
                if (!second.empty() && k < second.size()) model = model * double(1.0f - blend) + (glm::dmat4(second[k]) * b) * double(blend);
                j.position[n] = Vec3(world * model);
                j.set[n] = 1;
            }
        };
        auto joints = [&]() -> Joints& {
            Joints& j = byActor_[item.actor];
            if (j.position.empty()) j.position.assign(t.nodeCount(), Vec3(0.0)), j.set.assign(t.nodeCount(), 0);
            return j;
        };
        if (item.representation == Representation::KeyPose && item.keyPose.source) {
            const KeyPoseRef& ref = item.keyPose;
            if (ref.skin >= t.skins().size()) continue;
            const auto a = ref.source->palette(ref.skin, ref.pose[0]);
            const auto b = ref.blend != 0.0f ? ref.source->palette(ref.skin, ref.pose[1]) : std::span<const glm::mat4>{};
            place(joints(), t.skins()[ref.skin], a, b, ref.blend);
        } else if (item.skinPalette) {
            // The skin deforming the item's mesh: the actor-level level showing its drawable.
            int skin = -1;
            for (const VaLodLevel& level : t.rootGeometry().levels())
                if (level.drawable.get() == item.drawable) skin = level.skin;
            if (skin < 0 || std::size_t(skin) >= t.skins().size()) continue;
            place(joints(), t.skins()[std::size_t(skin)], {item.skinPalette, item.skinPaletteSize}, {}, 0.0f);
        }
    }
}

void DrawnJoints::compare(const DrawnJoints& reference, JointError& error) const {
    for (const auto& [actor, joints] : byActor_) {
        const auto ref = reference.byActor_.find(actor);
        if (ref == reference.byActor_.end()) continue;
        const std::size_t n = std::min(joints.position.size(), ref->second.position.size());
        for (std::size_t i = 0; i < n; ++i)
            if (joints.set[i] && ref->second.set[i]) error.addOne(joints.position[i], ref->second.position[i]);
    }
}

}  // namespace throng::testkit
