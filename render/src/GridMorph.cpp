#include "throng/render/GridMorph.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace throng {
namespace {

// Grid coordinates along one axis: 0, step, 2 step, ... and always the last pixel.
std::vector<int> gridLines(int size, int step) {
    std::vector<int> g;
    for (int i = 0; i < size - 1; i += step) g.push_back(i);
    g.push_back(size - 1);
    return g;
}

}  // namespace

Image morphImagesOnGrid(const Image& from, std::span<const FeatureLine> fromLines, const Image& to,
                        std::span<const FeatureLine> toLines, std::span<const FeatureLine> targetLines, float t,
                        const MorphParameters& parameters, int step) {
    if (step <= 1) return morphImages(from, fromLines, to, toLines, targetLines, t, parameters);
    if (!from.valid() || !to.valid()) throw std::invalid_argument("morphImagesOnGrid: an image is invalid");
    if (from.width != to.width || from.height != to.height) throw std::invalid_argument("morphImagesOnGrid: images of different sizes");
    if (fromLines.size() != targetLines.size() || toLines.size() != targetLines.size())
        throw std::invalid_argument("morphImagesOnGrid: the three line sets differ in size");
    if (!std::isfinite(t)) throw std::invalid_argument("morphImagesOnGrid: t is not finite");
    const std::vector<int> gx = gridLines(from.width, step), gy = gridLines(from.height, step);
    // Source positions in both images at every grid vertex, exactly.
    std::vector<glm::vec2> s0(gx.size() * gy.size()), s1(s0.size());
    for (std::size_t j = 0; j < gy.size(); ++j)
        for (std::size_t i = 0; i < gx.size(); ++i) {
            const glm::vec2 p(static_cast<float>(gx[i]) + 0.5f, static_cast<float>(gy[j]) + 0.5f);
            s0[j * gx.size() + i] = beierNeelySourcePosition(p, targetLines, fromLines, parameters);
            s1[j * gx.size() + i] = beierNeelySourcePosition(p, targetLines, toLines, parameters);
        }
    Image out;
    out.name = from.name + "~" + to.name;
    out.width = from.width;
    out.height = from.height;
    out.rgba.assign(from.rgba.size(), 0);
    std::size_t cy = 0;
    for (int y = 0; y < out.height; ++y) {
        while (cy + 2 < gy.size() && y >= gy[cy + 1]) ++cy;
        const float fy = gy.size() > 1 ? static_cast<float>(y - gy[cy]) / static_cast<float>(gy[cy + 1] - gy[cy]) : 0.0f;
        const std::size_t row0 = cy * gx.size(), row1 = std::min(cy + 1, gy.size() - 1) * gx.size();
        std::size_t cx = 0;
        for (int x = 0; x < out.width; ++x) {
            while (cx + 2 < gx.size() && x >= gx[cx + 1]) ++cx;
            const std::size_t cx1 = std::min(cx + 1, gx.size() - 1);
            const float fx = cx1 != cx ? static_cast<float>(x - gx[cx]) / static_cast<float>(gx[cx1] - gx[cx]) : 0.0f;
            const auto lerp2 = [&](const std::vector<glm::vec2>& s) {
                const glm::vec2 top = s[row0 + cx] * (1.0f - fx) + s[row0 + cx1] * fx;
                const glm::vec2 bottom = s[row1 + cx] * (1.0f - fx) + s[row1 + cx1] * fx;
                return top * (1.0f - fy) + bottom * fy;
            };
            float c0[4], c1[4];
            samplePremultiplied(from, lerp2(s0), c0);
            samplePremultiplied(to, lerp2(s1), c1);
            std::uint8_t* o = &out.rgba[(static_cast<std::size_t>(y) * out.width + x) * 4];
            for (int c = 0; c < 4; ++c) {
                const float v = c0[c] * (1.0f - t) + c1[c] * t;
                o[c] = static_cast<std::uint8_t>(std::floor(std::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f));
            }
        }
    }
    return out;
}

}  // namespace throng
