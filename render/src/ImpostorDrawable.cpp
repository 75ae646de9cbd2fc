#include "throng/render/ImpostorDrawable.h"

#include <stdexcept>

namespace throng {
namespace {

const ImpostorAtlas& checked(const std::shared_ptr<const ImpostorAtlas>& atlas) {
    if (!atlas) throw std::invalid_argument("ImpostorDrawable: argument 'atlas' is null");
    return *atlas;
}

}  // namespace

ImpostorDrawable::ImpostorDrawable(std::shared_ptr<const ImpostorAtlas> atlas)
    : Drawable("impostor " + checked(atlas).templateName() + "/" + atlas->clipName(),
               BoundingSphere(Vec3(atlas->worldCentre()), atlas->worldRadius()), 2),
      atlas_(std::move(atlas)) {}

}  // namespace throng
