#include "Silhouette.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace throng::test {

std::size_t Mask::count() const {
    return static_cast<std::size_t>(std::count(covered.begin(), covered.end(), std::uint8_t{1}));
}

Mask silhouetteOf(const Image& image, glm::u8vec3 clear, int tolerance) {
    Mask m{image.width, image.height, std::vector<std::uint8_t>(static_cast<std::size_t>(image.width) * image.height, 0)};
    for (std::size_t i = 0; i < m.covered.size(); ++i) {
        const std::uint8_t* p = &image.rgba[i * 4];
        for (int c = 0; c < 3; ++c)
            if (std::abs(int(p[c]) - int(clear[c])) > tolerance) m.covered[i] = 1;
    }
    return m;
}

Mask rasterise(std::span<const glm::dvec3> positions, std::span<const std::uint32_t> triangles, const Camera& camera,
               int width, int height) {
    Mask m{width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height, 0)};
    const Mat4 vp = camera.viewProjection();
    const Mat4& view = camera.view();
    // Window coordinates with y down (row 0 at the top), pixel centres at half integers.
    std::vector<glm::dvec2> window(positions.size());
    for (std::size_t i = 0; i < positions.size(); ++i) {
        const double depth = -(view * Vec4(positions[i], 1.0)).z;
        if (!(depth > camera.nearDistance() && depth < camera.farDistance()))
            throw std::invalid_argument("rasterise: vertex " + std::to_string(i) + " at depth " + std::to_string(depth) +
                                        " lies outside the near and far planes");
        const Vec4 clip = vp * Vec4(positions[i], 1.0);
        window[i] = {(clip.x / clip.w + 1.0) * 0.5 * width, (1.0 - clip.y / clip.w) * 0.5 * height};
    }
    for (std::size_t t = 0; t + 2 < triangles.size(); t += 3) {
        for (std::size_t k = 0; k < 3; ++k)
            if (triangles[t + k] >= positions.size())
                throw std::invalid_argument("rasterise: triangle " + std::to_string(t / 3) + " names vertex " +
                                            std::to_string(triangles[t + k]) + " of " + std::to_string(positions.size()));
        const glm::dvec2 a = window[triangles[t]], b = window[triangles[t + 1]], c = window[triangles[t + 2]];
        const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        if (area == 0.0) continue;  // degenerate: covers no pixel centre
        const double sign = area > 0 ? 1.0 : -1.0;  // both facings count
        const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
        const int x1 = std::min(width - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
        const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
        const int y1 = std::min(height - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
        const auto edge = [](const glm::dvec2& p, const glm::dvec2& q, double x, double y) {
            return (q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x);
        };
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) {
                const double px = x + 0.5, py = y + 0.5;
                if (sign * edge(a, b, px, py) >= 0 && sign * edge(b, c, px, py) >= 0 && sign * edge(c, a, px, py) >= 0)
                    m.covered[static_cast<std::size_t>(y) * width + x] = 1;
            }
    }
    return m;
}

double intersectionOverUnion(const Mask& a, const Mask& b) {
    if (a.width != b.width || a.height != b.height)
        throw std::invalid_argument("intersectionOverUnion: masks of " + std::to_string(a.width) + " x " +
                                    std::to_string(a.height) + " and " + std::to_string(b.width) + " x " +
                                    std::to_string(b.height));
    std::size_t both = 0, either = 0;
    for (std::size_t i = 0; i < a.covered.size(); ++i) {
        both += a.covered[i] && b.covered[i];
        either += a.covered[i] || b.covered[i];
    }
    return either == 0 ? 1.0 : double(both) / double(either);
}

Image maskDifference(const Mask& a, const Mask& b) {
    Image image;
    image.name = "mask difference";
    image.width = a.width;
    image.height = a.height;
    image.rgba.assign(a.covered.size() * 4, 0);
    for (std::size_t i = 0; i < a.covered.size(); ++i) {
        std::uint8_t* p = &image.rgba[i * 4];
        p[3] = 255;
        if (a.covered[i] && b.covered[i]) p[0] = p[1] = p[2] = 160;
        else if (a.covered[i]) p[0] = 255;
        else if (b.covered[i]) p[2] = 255;
    }
    return image;
}

}  // namespace throng::test
