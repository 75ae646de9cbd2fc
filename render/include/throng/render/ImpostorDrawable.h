#pragma once
// The far representation of an actor: a camera-facing quad showing its template's baked impostor.
// ActorProcessor puts one in the draw list for each actor beyond its impostor distance (placed at
// the actor's Reference Point); ImpostorBatcher turns those items into quad instances.

#include <memory>

#include "throng/render/ImpostorAtlas.h"
#include "throng/scenegraph/Drawable.h"

namespace throng {

/// A Drawable standing for an impostor atlas (bound: the baked volume; two triangles).
class ImpostorDrawable final : public Drawable {
public:
    /// Shows `atlas` (throws std::invalid_argument if null).
    explicit ImpostorDrawable(std::shared_ptr<const ImpostorAtlas> atlas);
    /// The atlas.
    const ImpostorAtlas& atlas() const { return *atlas_; }
    /// Shared handle to the atlas (renderers key their textures on it).
    const std::shared_ptr<const ImpostorAtlas>& atlasPtr() const { return atlas_; }

private:
    std::shared_ptr<const ImpostorAtlas> atlas_;
};

}  // namespace throng
