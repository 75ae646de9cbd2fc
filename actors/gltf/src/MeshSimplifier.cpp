#include "throng/gltf/MeshSimplifier.h"

#include <meshoptimizer.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace throng {
namespace {

// Keeps only the vertices `indices` use, in first-use order (good for the vertex cache too), and
// rewrites the indices.
std::shared_ptr<MeshData> compact(const MeshData& in, std::vector<std::uint32_t> indices) {
    constexpr std::uint32_t kUnused = ~std::uint32_t{0};
    std::vector<std::uint32_t> remap(in.vertexCount(), kUnused);
    auto out = std::make_shared<MeshData>();
    out->name = in.name;
    out->baseColor = in.baseColor;
    out->baseColorTexture = in.baseColorTexture;
    for (const MorphTarget& t : in.morphTargets) {  // the targets keep the kept vertices' offsets
        MorphTarget kept;
        kept.name = t.name;
        kept.defaultWeight = t.defaultWeight;
        out->morphTargets.push_back(std::move(kept));
    }
    for (std::uint32_t& i : indices) {
        if (remap[i] == kUnused) {
            remap[i] = static_cast<std::uint32_t>(out->positions.size());
            out->positions.push_back(in.positions[i]);
            if (!in.normals.empty()) out->normals.push_back(in.normals[i]);
            if (!in.texcoords.empty()) out->texcoords.push_back(in.texcoords[i]);
            if (!in.regions.empty()) out->regions.push_back(in.regions[i]);
            if (!in.joints0.empty()) out->joints0.push_back(in.joints0[i]), out->weights0.push_back(in.weights0[i]);
            if (!in.joints1.empty()) out->joints1.push_back(in.joints1[i]), out->weights1.push_back(in.weights1[i]);
            for (std::size_t k = 0; k < in.morphTargets.size(); ++k) {
                const MorphTarget& t = in.morphTargets[k];
                out->morphTargets[k].positions.push_back(t.positions[i]);
                if (!t.normals.empty()) out->morphTargets[k].normals.push_back(t.normals[i]);
            }
        }
        i = remap[i];
    }
    out->indices = std::move(indices);
    return out;
}

}  // namespace

SimplifiedMesh simplifyMesh(const MeshData& mesh, double triangleShare) {
    if (!(triangleShare > 0.0 && triangleShare <= 1.0))
        throw std::invalid_argument("simplifyMesh: '" + mesh.name + "': triangle share must be in (0, 1], got " + std::to_string(triangleShare));
    mesh.validate();
    SimplifiedMesh result;
    const std::size_t target = std::max<std::size_t>(3, static_cast<std::size_t>(std::llround(double(mesh.indices.size() / 3) * triangleShare)) * 3);
    if (target >= mesh.indices.size()) {
        result.mesh = compact(mesh, mesh.indices);
        return result;
    }
    const float* positions = &mesh.positions[0].x;
    const std::size_t stride = sizeof(glm::vec3);
    std::vector<std::uint32_t> indices(mesh.indices.size());
    float error = 0.0f;
    // A target error of 1 (the whole mesh) lets the triangle count decide.
    std::size_t count = meshopt_simplify(indices.data(), mesh.indices.data(), mesh.indices.size(), positions, mesh.vertexCount(), stride,
                                         target, 1.0f, 0, &error);
    if (double(count) > 1.5 * double(target)) {
        count = meshopt_simplifySloppy(indices.data(), mesh.indices.data(), mesh.indices.size(), positions, mesh.vertexCount(), stride,
                                       target, 1.0f, &error);
        result.sloppy = true;
    }
    indices.resize(count);
    result.error = double(error) * double(meshopt_simplifyScale(positions, mesh.vertexCount(), stride));
    result.mesh = compact(mesh, std::move(indices));
    return result;
}

}  // namespace throng
