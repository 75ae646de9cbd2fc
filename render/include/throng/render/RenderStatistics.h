#pragma once
// What GlRenderer did in one frame: the figures benchmarks and the town example print.

#include <cstdint>

namespace throng {

/// Work of one frame, reset by beginFrame().
struct RenderStatistics {
    std::uint64_t drawCalls = 0;           ///< glDraw* calls issued to draw (key-pose fills apart)
    std::uint64_t triangles = 0;           ///< triangles sent (all instances)
    std::uint64_t constantTriangles = 0;   ///< of those, constant faces shaded per vertex (RendererOptions::constantFaces)
    std::uint64_t flatLitTriangles = 0;    ///< of those, faces of one normal lit per vertex (same option)
    std::uint64_t instances = 0;           ///< mesh items drawn
    std::uint64_t gpuSkinnedVertices = 0;  ///< vertices skinned in the vertex shader
    std::uint64_t cpuSkinnedVertices = 0;  ///< vertices skinned on the CPU
    std::uint64_t skippedItems = 0;        ///< items whose drawable is not a MeshDrawable
    std::uint64_t meshUploads = 0;         ///< meshes uploaded to the GPU this frame
    std::uint64_t textureUploads = 0;      ///< textures uploaded to the GPU this frame
    std::uint64_t keyPoseInstances = 0;    ///< of `instances`, key-pose items (drawn from a key-pose cache)
    std::uint64_t keyPoseFills = 0;        ///< key-pose cache rows skinned this frame (transform feedback)
    std::uint64_t keyPoseFillCalls = 0;    ///< transform-feedback draws that skinned them (one per run of
                                           ///< consecutive rows; not counted in drawCalls)
    std::uint64_t keyPoseVertices = 0;     ///< cache vertices read (an interpolated instance reads two per vertex)
    std::uint64_t keyPoseCacheBytes = 0;   ///< GPU bytes held by the renderer's key-pose caches (every mesh and source)
    std::uint64_t morphInstances = 0;      ///< of `instances`, items drawn with a non-zero morph weight
    std::uint64_t morphTargetsRead = 0;    ///< non-zero morph weights applied, over those items (each reads its target per vertex)
    std::uint64_t fragments = 0;           ///< fragments that passed the depth test (RendererOptions::countFragments)
    double drawMs = 0;                     ///< CPU time spent in draw() (GL work may run later)
};

}  // namespace throng
