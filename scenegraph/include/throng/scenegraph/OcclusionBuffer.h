#pragma once
// A small CPU depth buffer of one frame's occluders, and the conservative test of bounding spheres
// against it (the Hi-Z technique: a pyramid of each 2 x 2 block's farthest depth).
//
// Conservative by construction, so that an actor with one visible pixel is never rejected:
//  - a pixel is written only where an occluder covers all of the pixel's square (inner coverage of
//    the occluder's convex silhouette), never where it covers only the pixel's centre;
//  - the depth written is the occluder's farthest front-surface depth over that square (the front
//    surface of a convex body is the farthest of its front faces' planes along each ray, and the
//    reciprocal depth of a plane is affine on the screen: its extremes lie at the square's corners);
//  - a sphere is hidden only if its nearest depth lies beyond the farthest depth of every pixel its
//    exact screen rectangle touches.
// Depths are stored as reciprocals (0 where nothing is drawn), so "nearest occluder" is a max and
// the pyramid keeps each block's min. Occluders crossing the near plane are clipped; an occluder
// the eye is inside is left out. Rows are filled by loops over flat arrays that the compiler
// vectorises.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "throng/scenegraph/BoundingSphere.h"
#include "throng/scenegraph/Math.h"

namespace throng {

class ByteReader;
class ByteWriter;
class Camera;

/// One frame's occlusion depth buffer.
class OcclusionBuffer {
public:
    /// A buffer of `width` x `height` pixels (each in [8, 4096]) covering the camera's viewport.
    /// Throws std::invalid_argument naming the bad argument.
    OcclusionBuffer(int width, int height);

    /// Starts a frame for `camera`: clears the buffer. Throws std::invalid_argument if the
    /// camera's projection is not a perspective one.
    void begin(const Camera& camera);
    /// Draws a convex occluder given by its 8 world corners (AxisBox::corner order: a box or any
    /// parallelepiped). Returns false when it drew nothing: the eye inside it, all of it behind
    /// the near plane or off the screen, degenerate or not finite.
    bool drawBox(const std::array<Vec3, 8>& corners);
    /// Ends the frame's drawing: builds the pyramid. Tests are valid until the next begin().
    void finish();
    /// Whether `sphere` (world space) is certainly hidden by what was drawn. False for empty or
    /// non-finite spheres and for spheres reaching the near plane. Thread-safe between finish()
    /// and the next begin().
    bool occluded(const BoundingSphere& sphere) const;
    /// The same answer as occluded(), always reached over the sphere's whole screen rectangle
    /// (occluded() first looks at the pixel under the sphere's centre); for tests.
    bool occludedOverRectangle(const BoundingSphere& sphere) const;

    /// Appends the frame as finish() left it (its camera and depths, not the pyramid) to `out`, for
    /// processes that test against it without drawing it (ranks posing their own actors).
    void write(ByteWriter& out) const;
    /// Makes this buffer the frame `in` holds (what write() wrote of a buffer of this size) and
    /// builds its pyramid: tests then answer as they do on the writer's. Throws
    /// std::invalid_argument naming what is wrong (another size, bytes cut short, a depth or a
    /// camera number that is not finite), the buffer unchanged.
    void read(ByteReader& in);

    /// Buffer width in pixels.
    int width() const { return width_; }
    /// Buffer height in pixels.
    int height() const { return height_; }
    /// Farthest depth (metres from the eye along the view axis) hidden by occluders at pixel
    /// (x, y), row 0 at the bottom; +infinity where nothing was drawn.
    double depthAt(int x, int y) const;
    /// Distance from the eye to the farthest corner of the near plane's rectangle (from begin()):
    /// geometry nearer than this may be cut open by the near plane.
    double nearReach() const { return nearReach_; }
    /// Pixels written by the last frame (one per pixel per occluder covering it).
    std::uint64_t pixelsWritten() const { return pixelsWritten_; }

private:
    // The test of occluded(), with `shortcut` whether to look at the centre's pixel first.
    bool test(const BoundingSphere& sphere, bool shortcut) const;

    struct Level {
        int width, height;
        std::vector<float> r;  // reciprocal depth
    };

    int width_, height_;
    std::vector<Level> levels_;   // level 0 is the buffer itself
    Mat4 view_{1.0};
    double sx_ = 1, sy_ = 1, ox_ = 0, oy_ = 0, near_ = 0.1, nearReach_ = 0.1;
    std::uint64_t pixelsWritten_ = 0;
    std::vector<float> rowMin_;   // scratch of drawBox and read
};

}  // namespace throng
