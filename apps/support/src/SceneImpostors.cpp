#include "throng/support/SceneImpostors.h"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "throng/render/ImpostorSet.h"
#include "throng/sim/Simulation.h"
#include "throng/support/ProgressBar.h"
#include "throng/support/StopSignals.h"

namespace throng::support {

ImpostorBakeOptions sceneBakeOptions(const sim::Simulation& world) {
    ImpostorBakeOptions bake;
    bake.cellSize = 64;
    switch (world.description().representation.impostorAtlas) {
        case sim::ImpostorAtlasStorage::Full: bake.storage = AtlasStorage::Full; break;
        case sim::ImpostorAtlasStorage::HalfKeyframes: bake.storage = AtlasStorage::HalfKeyframes; break;
        case sim::ImpostorAtlasStorage::Half: bake.storage = AtlasStorage::Half; break;
    }
    return bake;
}

std::unique_ptr<ImpostorSet> bakeSceneImpostors(const std::shared_ptr<GlContext>& context, const sim::Simulation& world, bool progress) {
    std::vector<ImpostorSet::Source> sources;
    for (const auto& t : world.templates()) sources.push_back({t.tmpl, t.clip});
    ImpostorBakeOptions bake = sceneBakeOptions(world);
    std::optional<ProgressBar> bar;
    if (progress) {
        bar.emplace("baking impostors", 1000);
        bake.progress = [&](int done, int total) {
            StopSignals::throwIfStopped();  // nothing baked is kept: a stop here stops at once
            bar->update(std::size_t(1000.0 * done / std::max(total, 1)), std::to_string(done) + "/" + std::to_string(total) + " key-frames");
        };
    }
    auto impostors = std::make_unique<ImpostorSet>(context, sources, bake);
    if (bar) bar->finish(std::to_string(impostors->size()) + " templates, " + std::to_string(impostors->textureBytes() >> 20) + " MiB of atlases");
    return impostors;
}

}  // namespace throng::support
