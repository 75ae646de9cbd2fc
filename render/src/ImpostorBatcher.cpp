#include "throng/render/ImpostorBatcher.h"

#include <cmath>

#include "throng/render/ImpostorDrawable.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/Stopwatch.h"

namespace throng {

ImpostorBatcher::ImpostorBatcher(MorphCache& cache, ImpostorViewChoice views) : cache_(&cache), views_(views) {}

ImpostorBatcher::ImpostorBatcher(ImpostorViewChoice views) : cache_(nullptr), views_(views) {}

void ImpostorBatcher::build(const DrawList& list, const Camera& camera) {
    Stopwatch watch;
    stats_ = {};
    instances_.clear();
    if (cache_) cache_->beginFrame();
    const Vec3 eye = camera.eye();
    for (const DrawItem& item : list.items()) {
        if (item.representation != Representation::Impostor) continue;
        const auto* d = dynamic_cast<const ImpostorDrawable*>(item.drawable);
        if (!d) continue;
        const ImpostorAtlas& atlas = d->atlas();
        const Mat4 world = item.world.toMat4();
        ImpostorInstance inst;
        inst.drawable = d;
        inst.tint = item.tint;
        inst.look = item.look;
        inst.centre = Vec3(world * Vec4(Vec3(atlas.worldCentre()), 1.0));
        // The eye in the actor's frame: the transpose of a rotation (scale cancels in the blend).
        const Vec3 toEye = eye - inst.centre;
        const glm::dmat3 r(world);
        const glm::vec3 local(glm::dot(r[0], toEye), glm::dot(r[1], toEye), glm::dot(r[2], toEye));
        inst.halfSize = atlas.worldRadius() * static_cast<float>(glm::length(r[0]));
        ViewBlend blend;
        if (views_.nearest) blend.views[0] = atlas.views().nearest(local);  // weights (1, 0, 0)
        else blend = atlas.views().blend(local, views_.smoothstep);
        inst.views = blend.views;
        inst.weights = blend.weights;
        double phase = std::fmod(item.clipTime / atlas.duration(), 1.0);
        if (!(phase >= 0.0)) phase = phase < 0.0 ? phase + 1.0 : 0.0;
        inst.keyframe = std::min(static_cast<int>(phase * atlas.keyframeCount()), atlas.keyframeCount() - 1);
        inst.phase = std::min(static_cast<float>(phase * atlas.keyframeCount()), std::nextafter(static_cast<float>(atlas.keyframeCount()), 0.0f));
        inst.origin = Vec3(world[3]);
        inst.axes = glm::mat3(glm::dmat3(world));
        for (int i = 0; i < 3; ++i)
            if (inst.weights[static_cast<std::size_t>(i)] > 0.0f && !atlas.cellStored(inst.views[static_cast<std::size_t>(i)], inst.keyframe)) {
                if (cache_)
                    inst.morphed[static_cast<std::size_t>(i)] = &cache_->request(atlas, inst.views[static_cast<std::size_t>(i)], inst.keyframe);
                ++stats_.droppedCells;
            }
        instances_.push_back(inst);
    }
    stats_.impostors = instances_.size();
    stats_.ms = watch.elapsedMs();
}

}  // namespace throng
