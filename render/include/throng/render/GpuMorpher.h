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

    /// The same morph without leaving the GL: the neighbours are layers `fromLayer` and `toLayer`
    /// of the 2-D array texture `cells`, the result (`size` x `size`, rows top first) is drawn and
    /// copied by the GL into layer `targetLayer` of the RGBA8 2-D array texture `target` (which may
    /// be `cells`); no upload, no read-back, so nothing waits for the GL. Texture names belong to
    /// this morpher's context. Throws std::invalid_argument for a zero name, a layer or size that
    /// does not fit, a bad line count or a non-finite t, std::runtime_error if the GL cannot draw.
    void morphInto(unsigned cells, int fromLayer, int toLayer, unsigned target, int targetLayer, int size,
                   std::span<const FeatureLine> fromLines, std::span<const FeatureLine> toLines,
                   std::span<const FeatureLine> targetLines, float t, const MorphParameters& parameters = {},
                   std::span<const LineAttributes> attributes = {});

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace throng
