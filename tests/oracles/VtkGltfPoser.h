#pragma once
// VTK's own reading of a glTF file, posed at a clip time: an implementation independent of
// Throng's loader, pose kernels and skinning, used as an oracle. vtkGLTFReader (VTK 9.1) samples the
// animation (UPDATE_TIME_STEP), builds the nodes' global transforms and skins every primitive on
// the CPU (ApplyDeformationsToGeometry, through vtkWeightedTransformFilter), then applies the mesh
// node's global transform. Its points are in the frame of the glTF default scene, in file units.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <vtkSmartPointer.h>

class vtkGLTFReader;

namespace throng::test {

/// Every primitive of the default scene, concatenated in VTK's block order (scene nodes depth
/// first, children in order, primitives in order).
struct VtkPosedMesh {
    std::vector<glm::dvec3> positions;            ///< file units, glTF scene frame
    std::vector<std::uint32_t> triangles;         ///< three indices into positions per triangle
    std::vector<std::size_t> primitiveVertices;   ///< vertex count of each primitive, in order
};

/// A glTF file read by vtkGLTFReader.
class VtkGltfPoser {
public:
    /// Reads the metadata of `path`. Throws std::runtime_error naming the file if VTK's pipeline
    /// fails to read it. (VTK's glTF loader only logs some problems, such as a sampler input
    /// without min and max, and skips what they concern: callers compare the counts.)
    explicit VtkGltfPoser(const std::string& path);
    ~VtkGltfPoser();
    VtkGltfPoser(const VtkGltfPoser&) = delete;
    VtkGltfPoser& operator=(const VtkGltfPoser&) = delete;

    /// Number of animations in the file.
    int animationCount() const;
    /// Index of the animation named `name`, or -1.
    int findAnimation(const std::string& name) const;
    /// Duration of animation `a` as VTK reports it (seconds).
    double duration(int a) const;

    /// The deformed mesh with only animation `a` enabled, at time `t` seconds (UPDATE_TIME_STEP),
    /// or at rest when `a` is -1. Throws std::runtime_error if the update fails, the reader reports
    /// an error, or no triangle comes out.
    VtkPosedMesh pose(int a, double t);

private:
    vtkGLTFReader& reader(int a);
    std::string path_;
    vtkSmartPointer<vtkGLTFReader> info_;                      // metadata only
    std::map<int, vtkSmartPointer<vtkGLTFReader>> readers_;    // one per animation: none resets another's nodes
};

}  // namespace throng::test
