#pragma once
// Settings of a GlRenderer, chosen at construction (most can be changed later with setOptions).

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

namespace throng {

/// Part of DRAW's work left out, to find where its time goes (benchmarks: the picture is not the
/// scene's). Each keeps everything else as configured.
enum class DrawProbe {
    None,              ///< draw as configured
    SetUpOnly,         ///< every triangle transformed, clipped and set up, then scissored to 8 x 8 pixels
    DepthOnly,         ///< colour writes off: rasterisation and the depth test, nothing written but depth
    NoDepthRejection,  ///< the depth test always passes: every rasterised fragment is shaded and written
    /// Rigid items drawn by the one-colour program (each triangle its vertex colour, nothing
    /// interpolated): the same triangles, order and depth test, the per-pixel shading left out.
    /// llvmpipe runs a fragment shader even with colour writes off, so DepthOnly cannot isolate it.
    OneColour,
};

/// How GlRenderer draws.
struct RendererOptions {
    int width = 0;                    ///< viewport width in pixels (0: keep the context's size)
    int height = 0;                   ///< viewport height in pixels (0: keep the context's size)
    glm::vec4 clearColor{0.55f, 0.66f, 0.80f, 1.0f};  ///< background, as written to the image (sRGB)
    bool instancing = true;           ///< draw items sharing a mesh in one instanced call
    bool forceCpuSkinning = false;    ///< skin on the CPU (skinMesh) instead of in the vertex shader
    bool cullBackFaces = true;        ///< skip triangles facing away (closed, counter-clockwise meshes)
    bool captureFrames = false;       ///< endFrame() reads the frame into lastFrame() before presenting
    bool flatTint = false;            ///< write each item's tint as is, unlit and untextured (ID renders; no constant faces)
    /// Write each pixel's body region (BodyRegion / 255 in red, alpha 1), unlit: the region maps of
    /// impostor atlases. No constant faces.
    bool regionIds = false;
    /// beginFrame clears colour and depth. Off when drawing into a frame another renderer has begun
    /// and will present (a VTK render window), so its picture and depth stay under ours.
    bool clear = true;
    /// Draws nearer items first (groups by their nearest instance, instances near to far), so the
    /// depth test rejects hidden fragments before they are shaded. Same picture, less shading.
    bool frontToBack = true;
    /// Shades triangles of one colour (one normal and one texture coordinate at their three
    /// vertices, rigid meshes, back faces culled) once per vertex instead of once per pixel: the
    /// same formula, evaluated where it cannot vary; triangles of one normal are lit once per vertex
    /// and textured per pixel. Other triangles are shaded per pixel.
    bool constantFaces = true;
    glm::vec3 lightDirection{0.35f, 0.85f, 0.40f};  ///< towards the sun, world space (normalised on use)
    glm::vec3 lightColor{0.85f, 0.82f, 0.75f};      ///< sun radiance (linear)
    glm::vec3 skyColor{0.40f, 0.45f, 0.55f};        ///< hemisphere light from above (linear)
    glm::vec3 groundColor{0.18f, 0.16f, 0.14f};     ///< hemisphere light from below (linear)
    DrawProbe probe = DrawProbe::None;  ///< work left out of each frame (benchmarks)
    /// Counts the fragments each draw() lets through the depth test (RenderStatistics::fragments).
    /// draw() then waits for the GL to finish its items: for benchmarks, not for frame times.
    bool countFragments = false;
};

}  // namespace throng
