#pragma once
// Shared by the render tests: a small headless renderer, hand-built draw lists, and golden-image
// comparison.
//
// Golden images live in tests/render/golden/. To rewrite them after an intended change, run the
// tests with THRONG_UPDATE_GOLDEN=1 in the environment, e.g.
//     THRONG_UPDATE_GOLDEN=1 ctest --preset dev -L render
// then look at every rewritten PNG before committing it. On a mismatch the actual image and a
// difference image are written to <build>/tests/render/output/.

#include <deque>
#include <memory>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "throng/testkit/ImageCompare.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/Image.h"
#include "throng/scenegraph/MeshData.h"
#include "throng/scenegraph/MeshDrawable.h"

namespace throng {
class GlRenderer;
}

namespace throng::test {

/// Test image size: small, so llvmpipe renders each in a few milliseconds.
constexpr int kWidth = 160;
constexpr int kHeight = 120;

/// A camera at `eye` looking at `target`, 45 degree field of view, aspect of the test images.
Camera makeCamera(const Vec3& eye, const Vec3& target);

/// A draw list with the storage its items point to (matrices and palettes at stable addresses).
class Scene {
public:
    /// Appends an item drawing `drawable` with `world`, `tint` and, if given, a skin palette.
    void add(std::shared_ptr<const Drawable> drawable, const Mat4& world, const glm::vec4& tint = glm::vec4(1.0f),
             const std::vector<glm::mat4>* palette = nullptr);
    /// The items, in the order added.
    const DrawList& list() const { return list_; }

private:
    std::vector<std::shared_ptr<const Drawable>> drawables_;
    std::deque<std::vector<glm::mat4>> palettes_;
    DrawList list_;
};

/// Renders one frame of `scene` seen by `camera` and reads it back.
Image renderFrame(GlRenderer& renderer, const Camera& camera, const Scene& scene);

/// A mesh drawable for `mesh`.
std::shared_ptr<const MeshDrawable> drawable(std::shared_ptr<const MeshData> mesh);

/// Number of pixels that differ from the clear colour of the default RendererOptions.
std::size_t coveredPixels(const Image& image);

/// Tolerance of golden comparisons (see GoldenImageTest.cpp for why).
struct GoldenTolerance {
    int threshold = 8;               ///< a channel may differ by this much and not count
    double maxFraction = 0.005;      ///< fraction of pixels allowed over the threshold
    double minPsnr = 35.0;           ///< dB
};

/// Compares `actual` with golden/<name>.png (or rewrites it when THRONG_UPDATE_GOLDEN=1). Returns
/// an empty string on success, else what failed; writes output/<name>-actual.png and -diff.png.
std::string compareWithGolden(const Image& actual, const std::string& name, const GoldenTolerance& tolerance = {});

/// What a pass/fail comparison of two frames says: empty when `a` and `b` agree under `t`, else
/// how many pixels differ and the PSNR.
std::string disagreement(const Image& a, const Image& b, const GoldenTolerance& t);

/// Writes `image` to output/<name>.png for a human to look at.
void writeOutput(const Image& image, const std::string& name);

}  // namespace throng::test
