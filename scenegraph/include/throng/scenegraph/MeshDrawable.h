#pragma once
// A Drawable backed by CPU mesh data, which GL renderers know how to draw.

#include <memory>

#include "throng/scenegraph/Drawable.h"
#include "throng/scenegraph/MeshData.h"

namespace throng {

/// Shows one MeshData; its bound and triangle count come from the mesh.
class MeshDrawable : public Drawable {
public:
    /// Wraps `mesh` (validated; throws std::invalid_argument if null or invalid).
    explicit MeshDrawable(std::shared_ptr<const MeshData> mesh);
    /// The mesh.
    const MeshData& mesh() const { return *mesh_; }
    /// Shared handle to the mesh (renderers key their GPU buffers on it).
    const std::shared_ptr<const MeshData>& meshPtr() const { return mesh_; }

private:
    struct Checked {};
    MeshDrawable(Checked, std::shared_ptr<const MeshData> mesh);
    std::shared_ptr<const MeshData> mesh_;
};

}  // namespace throng
