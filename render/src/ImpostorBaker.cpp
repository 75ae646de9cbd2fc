#include "throng/render/ImpostorBaker.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "throng/actors/ActorTemplate.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/render/GlContext.h"
#include "throng/render/GlRenderer.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/DrawList.h"

namespace throng {

struct ImpostorBaker::Impl {
    std::shared_ptr<GlContext> context;
    std::shared_ptr<const ActorTemplate> tmpl;
    const AnimationClip* clip = nullptr;
    ImpostorBakeOptions options;
    ViewHemisphere views;
    std::unique_ptr<GlRenderer> renderer;
    std::vector<std::uint32_t> boneChild;     // node index of each bone's child joint
    glm::vec3 centre{0.0f};
    float radius = 1.0f;
    // Pose workspace.
    std::vector<float> dofs;
    std::vector<Affine> model;
    std::vector<BoundingSphere> geometry, subtree;
    std::vector<Mat4> worlds;
    std::vector<std::vector<glm::mat4>> palettes;
    Mat4 rootMatrix{1.0};

    Impl(const ImpostorBakeOptions& o) : options(o), views(o.azimuths, o.elevations) {}

    // Poses the skeleton at `time` into `model` and `rootMatrix`.
    void pose(double time) {
        const ActorTemplate& t = *tmpl;
        dofs.assign(t.restDofs().begin(), t.restDofs().end());
        clip->sample(t, time, true, {}, dofs);
        rootMatrix = rootPoseMatrix(clip->sampleRoot(time, true));
        model.resize(t.nodeCount());
        computeModelTransforms(t, dofs, {}, model);
    }

    Camera camera(std::uint32_t view) const { return camera(views.direction(view)); }

    Camera camera(const glm::vec3& direction) const {
        const glm::dvec3 d = glm::normalize(glm::dvec3(direction));
        const glm::dvec3 c(centre);
        const double r = radius;
        Camera cam;
        cam.setLookAt(c + d * (4.0 * r), c, glm::dvec3(0, 1, 0));
        cam.setProjectionMatrix(glm::ortho(-r, r, -r, r, 0.5 * r, 8.0 * r));
        return cam;
    }

    glm::vec2 toPixel(const Mat4& viewProjection, const glm::dvec3& p) const {
        const glm::dvec4 clipPos = viewProjection * glm::dvec4(p, 1.0);
        const double s = options.cellSize;
        return {static_cast<float>((clipPos.x / clipPos.w * 0.5 + 0.5) * s),
                static_cast<float>((0.5 - 0.5 * clipPos.y / clipPos.w) * s)};
    }
};

ImpostorBaker::ImpostorBaker(std::shared_ptr<GlContext> context, std::shared_ptr<const ActorTemplate> tmpl, int clip,
                             const ImpostorBakeOptions& options) {
    if (!context) throw std::invalid_argument("ImpostorBaker: argument 'context' is null");
    if (!tmpl) throw std::invalid_argument("ImpostorBaker: argument 'tmpl' is null");
    if (clip < 0 || static_cast<std::size_t>(clip) >= tmpl->clips().size())
        throw std::invalid_argument("ImpostorBaker: template '" + tmpl->name() + "' has no clip " + std::to_string(clip));
    if (options.keyframes < 2) throw std::invalid_argument("ImpostorBaker: at least 2 key-frames");
    if (options.cellSize < 8 || options.cellSize > 4096) throw std::invalid_argument("ImpostorBaker: cell size out of range");
    impl_ = std::make_unique<Impl>(options);
    Impl& s = *impl_;
    s.context = std::move(context);
    s.tmpl = std::move(tmpl);
    s.clip = s.tmpl->clips()[static_cast<std::size_t>(clip)].get();
    if (!(s.clip->duration() > 0.0))
        throw std::invalid_argument("ImpostorBaker: clip '" + s.clip->name() + "' has no duration");
    RendererOptions ro;
    ro.width = ro.height = options.cellSize;
    ro.clearColor = glm::vec4(0.0f);
    s.context->makeCurrent();
    s.context->resize(options.cellSize, options.cellSize);
    s.renderer = std::make_unique<GlRenderer>(s.context, ro);

    const ActorTemplate& t = *s.tmpl;
    for (std::size_t i = 0; i < t.nodeCount(); ++i)
        if (t.nodes()[i].parent >= 0) s.boneChild.push_back(static_cast<std::uint32_t>(i));
    // The covered volume: every internal sphere of the figure over finely sampled poses.
    s.geometry.resize(t.nodeCount());
    s.subtree.resize(t.nodeCount());
    BoundingSphere all;
    const int samples = std::max(options.keyframes * 4, 32);
    for (int k = 0; k < samples; ++k) {
        s.pose(s.clip->duration() * k / samples);
        BoundingSphere whole = computeInternalSpheres(t, s.model, {}, s.geometry, s.subtree);
        if (whole.valid()) all.expandBy(whole.transformed(s.rootMatrix));
        for (const Affine& m : s.model) all.expandBy(glm::dvec3(s.rootMatrix * glm::dvec4(glm::dvec3(m.translation), 1.0)));
    }
    if (!all.valid() || !(all.radius() > 0.0)) all = BoundingSphere(Vec3(0.0, 1.0, 0.0), 1.0);
    s.centre = glm::vec3(all.center());
    s.radius = static_cast<float>(all.radius() * 1.02);
}

ImpostorBaker::~ImpostorBaker() = default;

const ViewHemisphere& ImpostorBaker::views() const { return impl_->views; }

Image ImpostorBaker::renderCell(double time, std::uint32_t view) { return renderCell(time, impl_->views.direction(view)); }

Image ImpostorBaker::renderCell(double time, const glm::vec3& toEye) {
    Impl& s = *impl_;
    const ActorTemplate& t = *s.tmpl;
    s.pose(time);
    DrawList list;
    s.worlds.clear();
    s.worlds.reserve(t.nodeCount() + 1);
    s.palettes.clear();
    s.palettes.reserve(t.rootGeometry().levels().size() + 1);
    const auto addItem = [&](const VaLodLevel& level, const Mat4& world, std::uint32_t part) {
        if (!level.drawable) return;
        s.worlds.push_back(world);
        DrawItem item;
        item.drawable = level.drawable.get();
        item.worldMatrix = &s.worlds.back();
        item.part = part;
        if (level.skin >= 0) {
            const Skin& skin = t.skins()[static_cast<std::size_t>(level.skin)];
            s.palettes.emplace_back(skin.joints.size());
            computeSkinPalette(t, skin, s.model, {}, s.palettes.back());
            item.skinPalette = s.palettes.back().data();
            item.skinPaletteSize = static_cast<std::uint32_t>(skin.joints.size());
        }
        list.add(item, level.drawable->primitiveCount());
    };
    if (!t.rootGeometry().empty()) addItem(t.rootGeometry().levels().front(), s.rootMatrix, 0);
    for (std::size_t i = 0; i < t.nodeCount(); ++i)
        if (!t.nodes()[i].geometry.empty())
            addItem(t.nodes()[i].geometry.levels().front(), s.rootMatrix * s.model[i].toDMat4(), static_cast<std::uint32_t>(i + 1));
    const Camera cam = s.camera(toEye);
    s.context->makeCurrent();
    s.renderer->beginFrame(cam);
    s.renderer->draw(list);
    Image image = s.renderer->readFrame();
    s.renderer->endFrame();
    image.name = t.name() + " t=" + std::to_string(time);
    return image;
}

std::vector<FeatureLine> ImpostorBaker::projectBones(double time, std::uint32_t view) {
    Impl& s = *impl_;
    s.pose(time);
    const Mat4 vp = s.camera(view).viewProjection();
    std::vector<FeatureLine> out;
    out.reserve(s.boneChild.size());
    for (std::uint32_t child : s.boneChild) {
        const auto parent = static_cast<std::size_t>(s.tmpl->nodes()[child].parent);
        const glm::dvec3 a = glm::dvec3(s.rootMatrix * glm::dvec4(glm::dvec3(s.model[parent].translation), 1.0));
        const glm::dvec3 b = glm::dvec3(s.rootMatrix * glm::dvec4(glm::dvec3(s.model[child].translation), 1.0));
        out.push_back({s.toPixel(vp, a), s.toPixel(vp, b)});
    }
    return out;
}

ImpostorAtlas ImpostorBaker::bake() {
    Impl& s = *impl_;
    const ActorTemplate& t = *s.tmpl;
    std::vector<std::string> names;
    for (std::uint32_t child : s.boneChild) names.push_back(t.nodes()[child].name);
    ImpostorAtlas atlas(t.name(), s.clip->name(), s.views, s.options.keyframes, s.clip->duration(), s.options.cellSize, names);
    atlas.setWorldBounds(s.centre, s.radius);
    // Bone importance: length in the rest pose (long bones move the most pixels).
    s.pose(0.0);
    std::vector<float> importance;
    for (std::uint32_t child : s.boneChild) importance.push_back(glm::length(s.model[child].translation - s.model[static_cast<std::size_t>(t.nodes()[child].parent)].translation));
    atlas.setBoneImportance(importance);
    for (int k = 0; k < s.options.keyframes; ++k) {
        const double time = s.clip->duration() * k / s.options.keyframes;
        for (std::uint32_t v = 0; v < s.views.viewCount(); ++v) {
            atlas.setCell(v, k, renderCell(time, v));
            const std::vector<FeatureLine> lines = projectBones(time, v);
            std::copy(lines.begin(), lines.end(), atlas.lines(v, k).begin());
        }
        if (s.options.progress) s.options.progress(k + 1, s.options.keyframes);
    }
    return atlas;
}

}  // namespace throng
