#pragma once
// The impostors of a scene: one atlas per template in use, baked from the clip its actors mostly
// play, with every other key-frame (and optionally every other view ring) dropped, regenerated at
// draw time (ImpostorBakeOptions::storage). Hands them to an
// ActorProcessor, which then draws far actors as impostor items.

#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "throng/render/ImpostorAtlas.h"
#include "throng/render/ImpostorBaker.h"
#include "throng/render/ImpostorDrawable.h"

namespace throng {

class ActorProcessor;
class ActorTemplate;
class GlContext;

/// Baked impostors of several templates.
class ImpostorSet {
public:
    /// A template and the clip to bake it from.
    struct Source {
        std::shared_ptr<const ActorTemplate> tmpl;  ///< the template
        int clip = 0;                               ///< its main clip
    };

    /// Bakes every source in `context` with `options` (its progress reports key-frames over all
    /// sources), drops what options.storage says, and restores the context's size afterwards. Throws
    /// as ImpostorBaker does, naming the source.
    ImpostorSet(std::shared_ptr<GlContext> context, std::span<const Source> sources, ImpostorBakeOptions options = {});

    /// Makes `processor` draw actors beyond `distance` (with `hysteresis`, metres) as impostors.
    void attach(ActorProcessor& processor, double distance, double hysteresis) const;
    /// Number of atlases.
    std::size_t size() const { return baked_.size(); }
    /// The drawable of atlas `i` (what impostor draw items point to).
    const std::shared_ptr<const ImpostorDrawable>& drawable(std::size_t i) const { return baked_[i].drawable; }
    /// Texture memory of all atlases, bytes.
    std::size_t textureBytes() const;

private:
    struct Baked {
        const ActorTemplate* tmpl;
        std::shared_ptr<const ImpostorDrawable> drawable;
        std::shared_ptr<const ImpostorAtlas> atlas;
    };
    std::vector<Baked> baked_;
};

}  // namespace throng
