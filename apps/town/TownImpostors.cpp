#include "TownImpostors.h"

#include "throng/actors/Actor.h"
#include "throng/actors/ActorGroup.h"
#include "throng/render/GlContext.h"
#include "throng/render/ImpostorBaker.h"

namespace throng::town {
namespace {

// Cells kept from frame to frame: every in-between cell of a few templates, so after the first
// frames a cell is morphed once and reused until it falls out.
constexpr std::size_t kCachedCells = 4096;

MorphCacheOptions cacheOptions() {
    MorphCacheOptions o;
    o.capacity = kCachedCells;
    return o;
}

// The clip time actor `item` shows, asked of its behaviour.
ImpostorBatcher::ClipTime clipTimes(const Crowd& crowd) {
    return [&crowd](const DrawItem& item, double time) {
        ActorId id = 0;
        if (const auto* group = dynamic_cast<const ActorGroup*>(item.node)) id = group->ids()[item.instance];
        else if (const auto* actor = dynamic_cast<const Actor*>(item.node)) id = actor->id();
        else return time;
        const Crowd::State& s = crowd.state();
        return s.behaviour[id]->clipTime(s.slot[id], time);
    };
}

}  // namespace

TownImpostors::TownImpostors(std::shared_ptr<GlContext> context, const sim::Simulation& world, int cellSize,
                             const std::function<void(int, int)>& progress)
    : gpu_(context), cache_(cacheOptions(), &gpu_), batcher_(cache_, false, clipTimes(world.crowd())), quads_(context) {
    // The baker renders cells in `context` at cell size; the frames go back to their size after.
    const int width = context->width(), height = context->height();
    const auto templates = world.templates();
    int done = 0;
    const int total = static_cast<int>(templates.size());
    for (const auto& t : templates) {
        ImpostorBakeOptions options;
        options.cellSize = cellSize;
        options.progress = [&](int k, int n) {
            if (progress) progress(done * n + k, total * n);
        };
        ImpostorBaker baker(context, t.tmpl, t.clip, options);
        auto atlas = std::make_shared<ImpostorAtlas>(baker.bake());
        atlas->dropOddKeyframes();  // the in-betweens are morphed at run time
        baked_.push_back({t.tmpl.get(), std::make_shared<ImpostorDrawable>(atlas), atlas});
        ++done;
    }
    context->makeCurrent();
    context->resize(width, height);
}

void TownImpostors::attach(ActorProcessor& processor, double distance, double hysteresis) const {
    for (const Baked& b : baked_) processor.setImpostor(*b.tmpl, b.drawable);
    processor.setImpostorDistance(distance, hysteresis);
}

void TownImpostors::draw(const DrawList& list, const Camera& camera, double time) {
    batcher_.build(list, camera, time);
    quads_.draw(camera, batcher_.instances());
}

std::size_t TownImpostors::textureBytes() const {
    std::size_t bytes = 0;
    for (const Baked& b : baked_) bytes += b.atlas->textureBytes();
    return bytes;
}

}  // namespace throng::town
