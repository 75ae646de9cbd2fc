#pragma once
// Beier-Neely morphing in a fragment shader: the run-time path that regenerates dropped impostor
// key-frames. Computes what morphImages() computes (same weights, same premultiplied bilinear
// sampling done by hand with texelFetch, same cross-dissolve), so the two agree to rounding.

#include <memory>
#include <span>

#include "throng/render/BeierNeely.h"
#include "throng/scenegraph/Image.h"

namespace throng {

class GlContext;

/// Morphs image pairs on the GPU of a GlContext and reads the result back.
class GpuMorpher {
public:
    /// Most feature lines one morph may use (uniform arrays in the shader).
    static constexpr std::size_t kMaxLines = 64;

    /// Compiles the morph program in `context`. Throws std::invalid_argument if it is null and
    /// std::runtime_error with the compiler's log if the shader fails.
    explicit GpuMorpher(std::shared_ptr<GlContext> context);
    ~GpuMorpher();
    GpuMorpher(const GpuMorpher&) = delete;
    GpuMorpher& operator=(const GpuMorpher&) = delete;

    /// Same contract and result as morphImages() (with its per-line `attributes`); also throws
    /// std::invalid_argument when there are more than kMaxLines lines. Uploads both images, draws
    /// one full-cell pass and reads it back.
    Image morph(const Image& from, std::span<const FeatureLine> fromLines, const Image& to,
                std::span<const FeatureLine> toLines, std::span<const FeatureLine> targetLines, float t,
                const MorphParameters& parameters = {}, std::span<const LineAttributes> attributes = {});

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace throng
