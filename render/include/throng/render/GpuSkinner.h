#pragma once
// Runs the renderer's own skinning vertex code on the GPU and reads the skinned vertices back
// (transform feedback): to check the GPU path against skinMesh(), or to bake key-poses on the GPU.

#include <memory>
#include <span>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "throng/scenegraph/MeshData.h"

namespace throng {

class GlContext;

/// GPU linear-blend skinning with read-back, sharing the shader code of GlRenderer.
class GpuSkinner {
public:
    /// Compiles the capture programs in `context`. Throws std::invalid_argument if it is null,
    /// std::runtime_error with the log if a shader fails.
    explicit GpuSkinner(std::shared_ptr<GlContext> context);
    ~GpuSkinner();
    GpuSkinner(const GpuSkinner&) = delete;
    GpuSkinner& operator=(const GpuSkinner&) = delete;

    /// Same contract as skinMesh() (same outputs, same errors), computed by the vertex shader. The
    /// mesh is uploaded on every call: this is for checks and baking, not for per-frame use.
    void skin(const MeshData& mesh, std::span<const glm::mat4> palette, std::span<glm::vec3> positions,
              std::span<glm::vec3> normals);

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace throng
