#include "throng/render/ViewHemisphere.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

namespace throng {
namespace {

constexpr float kTwoPi = 2.0f * std::numbers::pi_v<float>;

float smoother(float x) { return x * x * x * (x * (x * 6.0f - 15.0f) + 10.0f); }

}  // namespace

ViewHemisphere::ViewHemisphere(int azimuths, int elevations, float topElevation)
    : azimuths_(azimuths), elevations_(elevations), top_(topElevation) {
    if (azimuths < 3) throw std::invalid_argument("ViewHemisphere: azimuths must be >= 3, got " + std::to_string(azimuths));
    if (elevations < 1)
        throw std::invalid_argument("ViewHemisphere: elevations must be >= 1, got " + std::to_string(elevations));
    if (!(topElevation >= 0.0f && topElevation <= std::numbers::pi_v<float> / 2.0f))
        throw std::invalid_argument("ViewHemisphere: topElevation must be in [0, pi/2]");
}

float ViewHemisphere::azimuth(int a) const { return kTwoPi * static_cast<float>(a) / static_cast<float>(azimuths_); }

float ViewHemisphere::elevation(int e) const {
    return elevations_ == 1 ? 0.0f : top_ * static_cast<float>(e) / static_cast<float>(elevations_ - 1);
}

glm::vec3 ViewHemisphere::direction(std::uint32_t view) const {
    const int a = static_cast<int>(view % static_cast<std::uint32_t>(azimuths_));
    const int e = static_cast<int>(view / static_cast<std::uint32_t>(azimuths_));
    const float az = azimuth(a), el = elevation(e);
    return {std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az)};
}

std::uint32_t ViewHemisphere::nearest(const glm::vec3& toEye) const {
    std::uint32_t best = 0;
    float bestDot = -2.0f;
    const float len = glm::length(toEye);
    if (!(len > 0.0f) || !std::isfinite(len)) return 0;
    for (std::uint32_t v = 0; v < viewCount(); ++v) {
        const float d = glm::dot(direction(v), toEye / len);
        if (d > bestDot) bestDot = d, best = v;
    }
    return best;
}

ViewBlend ViewHemisphere::blend(const glm::vec3& toEye, bool smoothstep) const {
    ViewBlend out;
    const float len = glm::length(toEye);
    if (!(len > 0.0f) || !std::isfinite(len)) return out;
    const glm::vec3 d = toEye / len;
    // Grid coordinates: azimuth in columns (wrapping), elevation in rings (clamped to the grid:
    // the pole and directions below the rim fall onto the nearest ring, as seed 003 clamps to the
    // cell rather than extrapolating).
    float az = std::atan2(d.x, d.z);
    if (az < 0.0f) az += kTwoPi;
    float col = az / kTwoPi * static_cast<float>(azimuths_);
    if (!(col >= 0.0f && col < static_cast<float>(azimuths_))) col = 0.0f;  // atan2(0,0) and rounding
    const float el = std::asin(std::clamp(d.y, -1.0f, 1.0f));
    float row = elevations_ == 1 || top_ <= 0.0f ? 0.0f : el / top_ * static_cast<float>(elevations_ - 1);
    row = std::clamp(row, 0.0f, static_cast<float>(elevations_ - 1));
    const int a0 = std::min(static_cast<int>(col), azimuths_ - 1);
    const int a1 = (a0 + 1) % azimuths_;
    const int e0 = std::min(static_cast<int>(row), std::max(elevations_ - 2, 0));
    const int e1 = std::min(e0 + 1, elevations_ - 1);
    const float u = std::clamp(col - static_cast<float>(a0), 0.0f, 1.0f);
    const float v = e1 == e0 ? 0.0f : std::clamp(row - static_cast<float>(e0), 0.0f, 1.0f);
    const auto view = [&](int a, int e) { return static_cast<std::uint32_t>(e * azimuths_ + a); };
    // The grid cell splits along its diagonal into two triangles; barycentric weights in each.
    if (u >= v) {
        out.views = {view(a0, e0), view(a1, e0), view(a1, e1)};
        out.weights = {1.0f - u, u - v, v};
    } else {
        out.views = {view(a0, e0), view(a0, e1), view(a1, e1)};
        out.weights = {1.0f - v, v - u, u};
    }
    if (smoothstep) {
        float sum = 0.0f;
        for (float& w : out.weights) sum += (w = smoother(std::clamp(w, 0.0f, 1.0f)));
        if (sum > 0.0f)
            for (float& w : out.weights) w /= sum;
        else
            out.weights = {1.0f, 0.0f, 0.0f};
    }
    return out;
}

}  // namespace throng
