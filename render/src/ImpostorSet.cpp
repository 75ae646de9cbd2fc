#include "throng/render/ImpostorSet.h"

#include <stdexcept>

#include "throng/actors/ActorProcessor.h"
#include "throng/actors/ActorTemplate.h"
#include "throng/render/GlContext.h"

namespace throng {

ImpostorSet::ImpostorSet(std::shared_ptr<GlContext> context, std::span<const Source> sources, ImpostorBakeOptions options) {
    if (!context) throw std::invalid_argument("ImpostorSet: argument 'context' is null");
    // The baker renders cells in `context` at cell size; frames go back to their size after.
    const int width = context->width(), height = context->height();
    const auto progress = options.progress;
    const int total = static_cast<int>(sources.size());
    for (int done = 0; done < total; ++done) {
        const Source& source = sources[static_cast<std::size_t>(done)];
        options.progress = [&](int k, int n) {
            if (progress) progress(done * n + k, total * n);
        };
        try {
            ImpostorBaker baker(context, source.tmpl, source.clip, options);
            auto atlas = std::make_shared<ImpostorAtlas>(baker.bake());
            if (options.surfaceProxy) {
                atlas->setProxy(std::make_shared<const ProxyMesh>(baker.proxyMesh()));
                if (options.drawProxyVertices > 0)
                    atlas->setDrawProxy(std::make_shared<const ProxyMesh>(baker.proxyMesh(options.drawProxyVertices)));
            }
            atlas->drop(options.storage);  // what is dropped is regenerated at draw time
            baked_.push_back({source.tmpl.get(), std::make_shared<ImpostorDrawable>(atlas), atlas});
        } catch (const std::invalid_argument& e) {
            throw std::invalid_argument("ImpostorSet: source " + std::to_string(done) + ": " + e.what());
        }
    }
    context->makeCurrent();
    context->resize(width, height);
}

void ImpostorSet::attach(ActorProcessor& processor, double distance, double hysteresis) const {
    for (const Baked& b : baked_) processor.setImpostor(*b.tmpl, b.drawable);
    processor.setImpostorDistance(distance, hysteresis);
}

std::size_t ImpostorSet::textureBytes() const {
    std::size_t bytes = 0;
    for (const Baked& b : baked_) bytes += b.atlas->textureBytes();
    return bytes;
}

}  // namespace throng
