#include "throng/scenegraph/MeshDrawable.h"

#include <stdexcept>

namespace throng {
namespace {

const std::shared_ptr<const MeshData>& checked(const std::shared_ptr<const MeshData>& mesh) {
    if (!mesh) throw std::invalid_argument("MeshDrawable: argument 'mesh' is null");
    mesh->validate();
    return mesh;
}

}  // namespace

MeshDrawable::MeshDrawable(std::shared_ptr<const MeshData> mesh) : MeshDrawable(Checked{}, checked(mesh)) {}

MeshDrawable::MeshDrawable(Checked, std::shared_ptr<const MeshData> mesh)
    : Drawable(mesh->name, mesh->computeBound(), mesh->triangleCount(), static_cast<std::uint32_t>(mesh->morphTargets.size())),
      mesh_(std::move(mesh)) {}

}  // namespace throng
