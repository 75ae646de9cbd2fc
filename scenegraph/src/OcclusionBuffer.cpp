#include "throng/scenegraph/OcclusionBuffer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "throng/scenegraph/ByteStream.h"
#include "throng/scenegraph/Camera.h"

namespace throng {
namespace {

// Reciprocal depths written are scaled by this (a hair farther), tests need this much more: float
// rounding may then only ever keep an actor, never reject one.
constexpr float kWriteScale = 1.0f - 1e-4f;
constexpr double kTestScale = 1.0 + 1e-4;
// Silhouette edges are moved inwards by this share of a pixel.
constexpr double kEdgeInset = 1e-3;
// Pixels a sphere's centre must lie inside its screen rectangle for the centre's pixel to be taken
// as one of the rectangle's (rounding moves either by some 1e-12 pixel).
constexpr double kCentreMargin = 1e-3;

struct Point2 {
    double x, y;
};

double cross(const Point2& o, const Point2& a, const Point2& b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

// Convex hull of `p` (Andrew's monotone chain), counter-clockwise; returns its vertex count.
int convexHull(Point2* p, int n, Point2* hull) {
    std::sort(p, p + n, [](const Point2& a, const Point2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    int k = 0;
    for (int i = 0; i < n; ++i) {
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
        hull[k++] = p[i];
    }
    for (int i = n - 2, lower = k + 1; i >= 0; --i) {
        while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
        hull[k++] = p[i];
    }
    return std::max(k - 1, 0);
}

// Writes one row span of a box: per pixel the nearest reciprocal depth its `Faces` front faces
// allow (capped at the near plane), kept where it is nearer than what the row holds. One pass with
// the face count known to the compiler, so the loop vectorises; the same operations in the same
// order as the general loop in drawBox, so the same bits.
template <int Faces>
void writeSpan(float* row, int x0, int x1, float nearR, const float* slope, const float* offset) {
    float s[Faces], o[Faces];
    for (int f = 0; f < Faces; ++f) s[f] = slope[f], o[f] = offset[f];
    for (int x = x0; x <= x1; ++x) {
        float m = nearR;
        for (int f = 0; f < Faces; ++f) m = std::min(m, s[f] * static_cast<float>(x) + o[f]);
        row[x] = std::max(row[x], m * kWriteScale);
    }
}

void checkSize(int value, const char* name) {
    if (value < 8 || value > 4096)
        throw std::invalid_argument(std::string("OcclusionBuffer: argument '") + name + "' must be in [8, 4096], not " +
                                    std::to_string(value));
}

}  // namespace

OcclusionBuffer::OcclusionBuffer(int width, int height) : width_(width), height_(height) {
    checkSize(width, "width");
    checkSize(height, "height");
    int w = width, h = height;
    levels_.push_back(Level{w, h, std::vector<float>(std::size_t(w) * std::size_t(h), 0.0f)});
    while (w > 1 || h > 1) {
        w = (w + 1) / 2;
        h = (h + 1) / 2;
        levels_.push_back(Level{w, h, std::vector<float>(std::size_t(w) * std::size_t(h), 0.0f)});
    }
    rowMin_.resize(std::size_t(width));
}

void OcclusionBuffer::begin(const Camera& camera) {
    const Mat4& p = camera.projection();
    const bool perspective = p[0][1] == 0 && p[0][2] == 0 && p[0][3] == 0 && p[1][0] == 0 && p[1][2] == 0 && p[1][3] == 0 &&
                             p[2][3] == -1 && p[3][0] == 0 && p[3][1] == 0 && p[3][3] == 0 && p[0][0] > 0 && p[1][1] > 0;
    const double nearDistance = perspective ? p[3][2] / (p[2][2] - 1.0) : 0.0;
    if (!perspective || !(nearDistance > 0.0) || !std::isfinite(nearDistance))
        throw std::invalid_argument("OcclusionBuffer::begin: the camera's projection is not a perspective projection");
    view_ = camera.view();
    sx_ = p[0][0], sy_ = p[1][1], ox_ = p[2][0], oy_ = p[2][1], near_ = nearDistance;
    nearReach_ = 0.0;
    for (double x : {-1.0, 1.0})
        for (double y : {-1.0, 1.0}) {
            const double xq = (x + ox_) / sx_, yq = (y + oy_) / sy_;
            nearReach_ = std::max(nearReach_, near_ * std::sqrt(1.0 + xq * xq + yq * yq));
        }
    std::fill(levels_[0].r.begin(), levels_[0].r.end(), 0.0f);
    pixelsWritten_ = 0;
}

bool OcclusionBuffer::drawBox(const std::array<Vec3, 8>& corners) {
    // View space; d = -z is the depth along the view axis.
    std::array<Vec3, 8> v;
    Vec3 centre(0.0);
    for (int i = 0; i < 8; ++i) {
        v[i] = Vec3(view_ * Vec4(corners[i], 1.0));
        if (!std::isfinite(v[i].x) || !std::isfinite(v[i].y) || !std::isfinite(v[i].z)) return false;
        centre += v[i] / 8.0;
    }
    const double W = width_, H = height_;

    // Front faces (the eye outside their half-space): the reciprocal depth of each one's plane,
    // affine in pixel coordinates, r = a x + b y + c.
    struct Plane {
        double a, b, c;
    };
    std::array<Plane, 6> planes;
    int front = 0;
    for (int axis = 0; axis < 3; ++axis) {
        const int b1 = 1 << ((axis + 1) % 3), b2 = 1 << ((axis + 2) % 3);
        for (int side = 0; side < 2; ++side) {
            const int base = side ? (1 << axis) : 0;
            const Vec3 p0 = v[base];
            Vec3 n = glm::cross(v[base | b1] - p0, v[base | b2] - p0);
            const double len = glm::length(n);
            if (!(len > 1e-12)) return false;  // degenerate
            n /= len;
            if (glm::dot(n, p0 - centre) < 0.0) n = -n;
            const double k = glm::dot(n, p0);
            if (!(k < -1e-9)) continue;  // the eye is on this face's inner side
            // On the ray through NDC (X, Y): p = d (xq, yq, -1), xq = (X + ox) / sx; n.p = k.
            planes[front++] = Plane{2.0 * n.x / (k * sx_ * W), 2.0 * n.y / (k * sy_ * H),
                                    n.x * (ox_ - 1.0) / (k * sx_) + n.y * (oy_ - 1.0) / (k * sy_) - n.z / k};
        }
    }
    if (front == 0) return false;  // the eye is inside

    // The silhouette of the part in front of the near plane.
    std::array<Point2, 20> points;
    int count = 0;
    const auto project = [&](const Vec3& q) {
        const double d = -q.z;
        points[count++] = Point2{(sx_ * q.x / d - ox_ + 1.0) * 0.5 * W, (sy_ * q.y / d - oy_ + 1.0) * 0.5 * H};
    };
    for (int i = 0; i < 8; ++i) {
        const double di = -v[i].z;
        if (di >= near_) project(v[i]);
        for (int axis = 0; axis < 3; ++axis) {
            const int j = i | (1 << axis);
            if (j == i) continue;
            const double dj = -v[j].z;
            if ((di - near_) * (dj - near_) < 0.0) {
                const double t = (near_ - di) / (dj - di);
                Vec3 q = v[i] + t * (v[j] - v[i]);
                q.z = -near_;
                project(q);
            }
        }
    }
    if (count < 3) return false;
    std::array<Point2, 48> hull;  // the monotone chain may hold up to 2 * count before it closes
    const int n = convexHull(points.data(), count, hull.data());
    if (n < 3) return false;
    hull[n] = hull[0];

    double minY = hull[0].y, maxY = hull[0].y;
    for (int i = 1; i < n; ++i) minY = std::min(minY, hull[i].y), maxY = std::max(maxY, hull[i].y);
    const int y0 = std::max(0, static_cast<int>(std::ceil(minY))), y1 = std::min(height_ - 1, static_cast<int>(std::floor(maxY)) - 1);
    if (y0 > y1) return false;

    struct Edge {
        double a, b, c;  // a x + b y + c >= 0 inside, at the pixel corner where it is least
    };
    std::array<Edge, 21> edges;
    for (int i = 0; i < n; ++i) {
        const double A = -(hull[i + 1].y - hull[i].y), B = hull[i + 1].x - hull[i].x;
        const double C = -(A * hull[i].x + B * hull[i].y) + std::min(A, 0.0) + std::min(B, 0.0) - kEdgeInset * (std::abs(A) + std::abs(B));
        edges[i] = Edge{A, B, C};
    }
    const float nearR = static_cast<float>(1.0 / near_);
    std::array<float, 6> slope, offset;
    for (int f = 0; f < front; ++f) slope[f] = static_cast<float>(planes[f].a);

    std::vector<float>& r = levels_[0].r;
    bool drew = false;
    for (int y = y0; y <= y1; ++y) {
        double lo = 0.0, hi = W - 1.0;
        for (int i = 0; i < n && lo <= hi; ++i) {
            const Edge& e = edges[i];
            const double k = e.b * y + e.c;
            if (e.a > 1e-12) lo = std::max(lo, std::ceil(-k / e.a));
            else if (e.a < -1e-12) hi = std::min(hi, std::floor(-k / e.a));
            else if (k < 0.0) hi = -1.0;
        }
        if (lo > hi) continue;
        const int x0 = static_cast<int>(lo), x1 = static_cast<int>(hi);
        for (int f = 0; f < front; ++f)
            offset[f] = static_cast<float>(planes[f].b * y + planes[f].c + std::min(planes[f].a, 0.0) + std::min(planes[f].b, 0.0));
        float* row = r.data() + std::size_t(y) * std::size_t(width_);
        switch (front) {  // a box shows at most three faces; the others take the general loop
            case 1: writeSpan<1>(row, x0, x1, nearR, slope.data(), offset.data()); break;
            case 2: writeSpan<2>(row, x0, x1, nearR, slope.data(), offset.data()); break;
            case 3: writeSpan<3>(row, x0, x1, nearR, slope.data(), offset.data()); break;
            default: {
                float* rowMin = rowMin_.data();
                for (int x = x0; x <= x1; ++x) rowMin[x] = nearR;
                for (int f = 0; f < front; ++f) {
                    const float s = slope[f], o = offset[f];
                    for (int x = x0; x <= x1; ++x) rowMin[x] = std::min(rowMin[x], s * static_cast<float>(x) + o);
                }
                for (int x = x0; x <= x1; ++x) row[x] = std::max(row[x], rowMin[x] * kWriteScale);
            }
        }
        pixelsWritten_ += std::uint64_t(x1 - x0 + 1);
        drew = true;
    }
    return drew;
}

void OcclusionBuffer::finish() {
    for (std::size_t l = 1; l < levels_.size(); ++l) {
        const Level& below = levels_[l - 1];
        Level& level = levels_[l];
        for (int y = 0; y < level.height; ++y) {
            const int yb0 = 2 * y, yb1 = std::min(2 * y + 1, below.height - 1);
            for (int x = 0; x < level.width; ++x) {
                const int xb0 = 2 * x, xb1 = std::min(2 * x + 1, below.width - 1);
                const float* r0 = below.r.data() + std::size_t(yb0) * std::size_t(below.width);
                const float* r1 = below.r.data() + std::size_t(yb1) * std::size_t(below.width);
                level.r[std::size_t(y) * std::size_t(level.width) + std::size_t(x)] =
                    std::min(std::min(r0[xb0], r0[xb1]), std::min(r1[xb0], r1[xb1]));
            }
        }
    }
}

namespace {

// What write() puts before the depths: the camera as begin() took it.
struct BufferHead {
    std::int32_t width, height;
    double view[16];
    double sx, sy, ox, oy, near, nearReach;
};

}  // namespace

void OcclusionBuffer::write(ByteWriter& out) const {
    BufferHead h{};
    h.width = width_, h.height = height_;
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) h.view[4 * c + r] = view_[c][r];
    h.sx = sx_, h.sy = sy_, h.ox = ox_, h.oy = oy_, h.near = near_, h.nearReach = nearReach_;
    out.put(h);
    out.putSpan(std::span<const float>(levels_[0].r));
}

void OcclusionBuffer::read(ByteReader& in) {
    const auto h = in.get<BufferHead>("an occlusion buffer's camera");
    if (h.width != width_ || h.height != height_)
        throw std::invalid_argument(in.source() + ": an occlusion buffer of " + std::to_string(h.width) + " x " + std::to_string(h.height) +
                                    " pixels, this one has " + std::to_string(width_) + " x " + std::to_string(height_));
    bool finite = true;
    for (const double v : h.view) finite = finite && std::isfinite(v);
    for (const double v : {h.sx, h.sy, h.ox, h.oy, h.near, h.nearReach}) finite = finite && std::isfinite(v);
    if (!finite || !(h.near > 0.0)) throw std::invalid_argument(in.source() + ": an occlusion buffer's camera holds a number that is not finite");
    const std::span<const std::byte> depths = in.take(levels_[0].r.size() * sizeof(float), "an occlusion buffer's depths");
    // Reciprocal depths: finite and not negative (0 where nothing was drawn). Checked in a copy.
    std::vector<float>& r = rowMin_;
    r.resize(levels_[0].r.size());
    std::memcpy(r.data(), depths.data(), depths.size());
    for (std::size_t i = 0; i < r.size(); ++i)
        if (!std::isfinite(r[i]) || r[i] < 0.0f)
            throw std::invalid_argument(in.source() + ": an occlusion buffer's depth at pixel " + std::to_string(i) + " is not a depth");
    levels_[0].r.swap(r);
    r.resize(std::size_t(width_));
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) view_[c][row] = h.view[4 * c + row];
    sx_ = h.sx, sy_ = h.sy, ox_ = h.ox, oy_ = h.oy, near_ = h.near, nearReach_ = h.nearReach;
    pixelsWritten_ = 0;
    finish();
}

bool OcclusionBuffer::occluded(const BoundingSphere& sphere) const { return test(sphere, true); }

bool OcclusionBuffer::occludedOverRectangle(const BoundingSphere& sphere) const { return test(sphere, false); }

bool OcclusionBuffer::test(const BoundingSphere& sphere, bool shortcut) const {
    if (!sphere.valid()) return false;
    const Vec3 c(view_ * Vec4(sphere.center(), 1.0));
    const double d = -c.z, rho = sphere.radius();
    if (!std::isfinite(d) || !(d - rho > near_)) return false;
    const float need = static_cast<float>(kTestScale / (d - rho));
    if (shortcut) {
        // Most spheres tested are visible, and the pixel under the centre already shows it: one
        // pixel no nearer than the sphere inside its rectangle is enough (the pyramid's texels
        // are minima, so the full test below would meet it and answer the same). The centre's
        // pixel lies inside that rectangle when its distance to the rectangle's edges, at least
        // the half-angle the sphere subtends in pixels, dwarfs any rounding.
        const double px = (sx_ * (c.x / d) - ox_ + 1.0) * 0.5 * width_, py = (sy_ * (c.y / d) - oy_ + 1.0) * 0.5 * height_;
        const double mx = sx_ * 0.5 * width_ * rho / (std::abs(c.x) + d), my = sy_ * 0.5 * height_ * rho / (std::abs(c.y) + d);
        if (px >= 0.0 && px < width_ && py >= 0.0 && py < height_ && mx > kCentreMargin && my > kCentreMargin) {
            const float r = levels_[0].r[std::size_t(py) * std::size_t(width_) + std::size_t(px)];
            if (!(r > need)) return false;
        }
    }
    // The exact screen extent: the tangents from the eye to the sphere, axis by axis.
    const auto extent = [&](double x, double scale, double offset, double size, int& i0, int& i1) {
        const double t = std::sqrt(x * x + d * d - rho * rho);
        const double lo = (x * t - d * rho) / (d * t + x * rho), hi = (x * t + d * rho) / (d * t - x * rho);
        const double p0 = (scale * lo - offset + 1.0) * 0.5 * size, p1 = (scale * hi - offset + 1.0) * 0.5 * size;
        if (!std::isfinite(p0) || !std::isfinite(p1) || p1 < 0.0 || p0 >= size) return false;
        i0 = static_cast<int>(std::floor(std::max(p0, 0.0)));
        i1 = static_cast<int>(std::floor(std::min(p1, size - 1.0)));
        return true;
    };
    int x0, x1, y0, y1;
    if (!extent(c.x, sx_, ox_, width_, x0, x1) || !extent(c.y, sy_, oy_, height_, y0, y1)) return false;
    std::size_t l = 0;
    while (l + 1 < levels_.size() && ((x1 >> l) - (x0 >> l) > 3 || (y1 >> l) - (y0 >> l) > 3)) ++l;
    const Level& level = levels_[l];
    for (int y = y0 >> l; y <= (y1 >> l); ++y) {
        const float* row = level.r.data() + std::size_t(y) * std::size_t(level.width);
        for (int x = x0 >> l; x <= (x1 >> l); ++x)
            if (!(row[x] > need)) return false;
    }
    return true;
}

double OcclusionBuffer::depthAt(int x, int y) const {
    if (x < 0 || y < 0 || x >= width_ || y >= height_)
        throw std::out_of_range("OcclusionBuffer::depthAt: pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is outside the buffer");
    const float r = levels_[0].r[std::size_t(y) * std::size_t(width_) + std::size_t(x)];
    return r > 0.0f ? 1.0 / r : std::numeric_limits<double>::infinity();
}

}  // namespace throng
