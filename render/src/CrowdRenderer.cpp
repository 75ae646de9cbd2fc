#include "throng/render/CrowdRenderer.h"

#include <algorithm>
#include <cmath>

#include "throng/render/ImageOverlay.h"

#include <glad/gl.h>

#include <stdexcept>
#include <string>

#include "throng/render/GlContext.h"
#include "throng/render/GlRenderer.h"
#include "throng/render/GpuMorpher.h"
#include "throng/render/ImpostorDrawable.h"
#include "throng/render/ScaledFrame.h"
#include "throng/render/TextOverlay.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/Stopwatch.h"

namespace throng {

CrowdRenderer::CrowdRenderer(std::shared_ptr<GlContext> context, const CrowdRendererOptions& options)
    : context_(std::move(context)), options_(options) {
    if (!context_) throw std::invalid_argument("CrowdRenderer: argument 'context' is null");
    setRenderScale(options_.renderScale);
    meshes_ = std::make_unique<GlRenderer>(context_, options_.meshes);
    gpuTimer_ = std::make_unique<GpuPassTimer>(*context_);
}

CrowdRenderer::~CrowdRenderer() = default;

void CrowdRenderer::beginFrame(const Camera& camera) {
    camera_ = camera;
    stats_ = CrowdRenderStatistics{};
    if (scaledFrame_) scaled_->end();  // an earlier frame that threw before its end
    scaledFrame_ = options_.renderScale < 1.0f;
    if (scaledFrame_) {
        if (!scaled_) scaled_ = std::make_unique<ScaledFrame>(*context_);
        scaled_->begin(options_.renderScale);
    }
    const GlContext::DrawTarget target = context_->drawTarget();
    stats_.renderWidth = target.width, stats_.renderHeight = target.height;
    gpuTimer_->beginFrame();
    meshes_->beginFrame(camera);
}

void CrowdRenderer::draw(const DrawList& list) {
    Stopwatch watch;
    auto finish = [&] {
        if (!options_.finishPasses) return;
        context_->makeCurrent();
        context_->gl().Finish();
    };
    sceneItems_.clear();
    actorItems_.clear();
    bool impostors = false;
    for (const DrawItem& item : list.items()) {
        if (item.representation == Representation::Impostor) {
            impostors = true;
        } else if (item.representation == Representation::KeyPose) {  // an actor's, whatever its actor field says
            actorItems_.add(item, 0);
            ++stats_.keyPoseItems;
        } else if (item.actor == kNoActor) {
            if (options_.drawScene) sceneItems_.add(item, 0);
        } else {
            actorItems_.add(item, 0);
            stats_.skinnedItems += item.skinPaletteSize > 0;
        }
    }
    stats_.sceneItems += sceneItems_.size();
    gpuTimer_->begin(GpuPass::Town);
    meshes_->draw(sceneItems_);
    gpuTimer_->end();
    finish();
    stats_.sceneMs += watch.elapsedMs();
    watch.restart();
    gpuTimer_->begin(GpuPass::Meshes);
    meshes_->draw(actorItems_);
    gpuTimer_->end();
    finish();
    stats_.meshes = meshes_->statistics();
    stats_.meshMs += watch.elapsedMs();
    if (!impostors) return;
    if (!batcher_) {  // the first impostor: build the impostor machinery
        if (options_.morphing == ImpostorMorphing::FrameCache) {
            if (options_.gpuMorph) gpu_ = std::make_unique<GpuMorpher>(context_);
            cache_ = std::make_unique<MorphCache>(options_.morph, gpu_.get());
            batcher_ = std::make_unique<ImpostorBatcher>(*cache_, options_.views);
        } else {
            batcher_ = std::make_unique<ImpostorBatcher>(options_.views);
        }
        makeQuads();
    }
    watch.restart();
    gpuTimer_->begin(GpuPass::Impostors);  // cells morphed on the GPU, uploads and the quads
    batcher_->build(list, camera_);
    stats_.impostors = batcher_->statistics();
    if (cache_) stats_.morphs = cache_->statistics();
    stats_.impostorBatchMs += watch.elapsedMs();
    watch.restart();
    context_->makeCurrent();
    quads_->draw(camera_, batcher_->instances());
    gpuTimer_->end();
    finish();
    stats_.quads = quads_->statistics();
    const double quadMs = watch.elapsedMs();
    if (cache_) {
        stats_.cellsMorphed = stats_.morphs.synthesized;
        stats_.morphMs = stats_.morphs.morphMs;
        stats_.impostorDrawMs += quadMs;
    } else {  // the pool's morphing is impostor work before the quads, whatever pass issues it
        stats_.cellsMorphed = stats_.quads.cellsMorphed;
        stats_.morphMs = stats_.quads.morphMs;
        stats_.impostorBatchMs += stats_.quads.morphMs;
        stats_.impostorDrawMs += quadMs - stats_.quads.morphMs;
    }
}

void CrowdRenderer::makeQuads() {
    if (quads_) return;
    ImpostorRendererOptions o = options_.impostors;
    o.warped = options_.views.warped;
    // FrameCache: a layer per morphed cell of the frame, as the frame cache always had.
    if (options_.morphing == ImpostorMorphing::FrameCache) o.poolSlots = std::max(o.poolSlots, 256);
    quads_ = std::make_unique<ImpostorRenderer>(context_, o);
}

void CrowdRenderer::setMorphBudget(int budget) {
    if (budget < -1) throw std::invalid_argument("CrowdRenderer: morph budget must be >= -1, not " + std::to_string(budget));
    options_.impostors.morphBudget = budget;
    if (quads_) quads_->setMorphBudget(budget);
}

void CrowdRenderer::preloadImpostors(std::span<const std::shared_ptr<const ImpostorDrawable>> drawables) {
    if (drawables.empty()) return;
    makeQuads();
    context_->makeCurrent();
    for (const auto& d : drawables)
        if (d) quads_->preload(*d);
}

void CrowdRenderer::setRenderScale(float scale) {
    if (!(scale > 0.0f && scale <= 1.0f))
        throw std::invalid_argument("CrowdRenderer: render scale must be above 0 and at most 1, not " + std::to_string(scale));
    options_.renderScale = scale;
}

void CrowdRenderer::endFrame() {
    Stopwatch watch;
    finishImage();
    gpuTimer_->end();
    Stopwatch present;
    meshes_->endFrame();
    stats_.presentMs = present.elapsedMs();
    gpuTimer_->collect();
    stats_.gpu = gpuTimer_->latest();
    stats_.gpuFramesBehind = stats_.gpu.frame < 0 ? -1 : gpuTimer_->frame() - stats_.gpu.frame;
    stats_.endFrameMs = watch.elapsedMs() + finishMs_;
    finished_ = false;
    finishMs_ = 0.0;
}

void CrowdRenderer::finishImage() {
    if (finished_) return;
    finished_ = true;
    Stopwatch watch;
    gpuTimer_->begin(GpuPass::Finish);
    if (scaledFrame_) {  // the overlays below are drawn at full resolution, over the scaled-up frame
        scaled_->end();
        scaledFrame_ = false;
    }
    if (!overlayImage_.rgba.empty()) {
        if (!imageOverlay_) imageOverlay_ = std::make_unique<ImageOverlay>(*context_);
        // Bottom-right, a third of the frame's width, the image's own aspect.
        const int w = context_->width() / 3, h = w * overlayImage_.height / std::max(overlayImage_.width, 1);
        imageOverlay_->draw(overlayImage_, context_->width() - w - 12, context_->height() - h - 12, w, h);
    }
    if (!captions_.empty()) {
        if (!overlay_) overlay_ = std::make_unique<TextOverlay>(*context_);
        const Mat4 viewProjection = camera_.projection() * camera_.view();
        const double w = context_->width(), h = context_->height();
        constexpr float kScale = 1.5f;  // the font's 6 x 12 pixels, times this
        for (const Caption& c : captions_) {
            const Vec4 clip = viewProjection * Vec4(c.position, 1.0);
            if (!(clip.w > 0.0)) continue;  // behind the eye
            const double x = (0.5 + 0.5 * clip.x / clip.w) * w, y = (0.5 - 0.5 * clip.y / clip.w) * h;
            const double width = 6.0 * kScale * double(c.text.size());
            if (x + 0.5 * width < 0.0 || x - 0.5 * width > w || y < 0.0 || y > h) continue;
            overlay_->draw(c.text, int(std::lround(x - 0.5 * width)), int(std::lround(y - 14.0 * kScale)), kScale);
        }
    }
    if (!overlayText_.empty()) {
        if (!overlay_) overlay_ = std::make_unique<TextOverlay>(*context_);
        overlay_->draw(overlayText_, 12, 12, 1.6f);
    }
    finishMs_ = watch.elapsedMs();
}

std::size_t CrowdRenderer::impostorTextureBytes() const { return quads_ ? quads_->textureBytes() : 0; }

Image CrowdRenderer::readFrame() { return meshes_->readFrame(); }

}  // namespace throng
