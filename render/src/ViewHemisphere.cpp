#include "throng/render/ViewHemisphere.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

#include "throng/render/SimplexClamp.h"

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
    directions_.reserve(viewCount());
    for (std::uint32_t v = 0; v < viewCount(); ++v) {
        const int a = static_cast<int>(v % static_cast<std::uint32_t>(azimuths_)), e = static_cast<int>(v / static_cast<std::uint32_t>(azimuths_));
        const float az = azimuth(a), el = elevation(e);
        directions_.push_back({std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az)});
    }
}

float ViewHemisphere::azimuth(int a) const { return kTwoPi * static_cast<float>(a) / static_cast<float>(azimuths_); }

float ViewHemisphere::elevation(int e) const {
    return elevations_ == 1 ? 0.0f : top_ * static_cast<float>(e) / static_cast<float>(elevations_ - 1);
}

glm::vec3 ViewHemisphere::direction(std::uint32_t view) const { return directions_.at(view); }

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
    // The eye's column: the grid's columns are bounded by meridians, great circles, so the column
    // holds the eye exactly. Its rings are small circles (constant elevation), which the cells'
    // triangles (great-circle sides) do not follow: near a ring, the triangle holding the eye may
    // belong to the cell above or below the one its elevation names, so those are tried too.
    float az = std::atan2(d.x, d.z);
    if (az < 0.0f) az += kTwoPi;
    float col = az / kTwoPi * static_cast<float>(azimuths_);
    if (!(col >= 0.0f && col < static_cast<float>(azimuths_))) col = 0.0f;  // atan2(0,0) and rounding
    const int a0 = std::min(static_cast<int>(col), azimuths_ - 1);
    const int a1 = (a0 + 1) % azimuths_;
    const float el = std::asin(std::clamp(d.y, -1.0f, 1.0f));
    float row = elevations_ == 1 || top_ <= 0.0f ? 0.0f : el / top_ * static_cast<float>(elevations_ - 1);
    row = std::clamp(row, 0.0f, static_cast<float>(elevations_ - 1));
    const int cells = std::max(elevations_ - 1, 1);  // cells up the column (one ring: one flat cell)
    const int named = std::min(static_cast<int>(row), cells - 1);
    const auto view = [&](int a, int e) { return static_cast<std::uint32_t>(std::min(e, elevations_ - 1) * azimuths_ + a); };
    // Each candidate triangle: the eye's ray through its plane (a central projection: a direction on
    // the great circle between two views lands on the side between them, so the two triangles that
    // share that side agree there), clamped to the triangle against its sides and corners (seed 003
    // §4.1.2); the triangle whose clamped point is nearest the eye's direction wins (seed 003 §4.2:
    // the least extrapolation; 0 for the triangle holding the eye).
    float best = 3.0f;
    constexpr float kHolds = 1e-6f;  // 1 - cos of about a twentieth of a degree: rounding
    const auto tryTriangle = [&](const std::array<std::uint32_t, 3>& views) {
        const std::array<glm::vec3, 3> corners{directions_[views[0]], directions_[views[1]], directions_[views[2]]};
        const glm::vec3 normal = glm::cross(corners[1] - corners[0], corners[2] - corners[0]);
        // The ray meets the plane where d * t, t = (n . c0) / (n . d), is positive (either winding).
        const float across = glm::dot(normal, d), offset = glm::dot(normal, corners[0]);
        const glm::vec3 onPlane = across * offset > 1e-6f * glm::dot(normal, normal) ? d * (offset / across) : d;
        const std::array<float, 3> weights = clampedBarycentric(corners, onPlane);
        float away = 0.0f;  // inside (every weight above 0): the ray's own point
        if (!(weights[0] > 0.0f && weights[1] > 0.0f && weights[2] > 0.0f) || onPlane == d) {
            const glm::vec3 clamped = weights[0] * corners[0] + weights[1] * corners[1] + weights[2] * corners[2];
            const float clampedLength = glm::length(clamped);
            away = clampedLength > 0.0f ? 1.0f - glm::dot(clamped, d) / clampedLength : 2.0f;
        }
        if (away < best - 1e-7f) {
            best = away;
            out.views = views;
            out.weights = weights;
        }
    };
    // A cell's two triangles, the one on the eye's side of their shared diagonal (a great circle)
    // first, the other only when the first does not hold the eye.
    const auto tryCell = [&](int e0) {
        const int e1 = e0 + 1;
        const std::array<std::uint32_t, 3> lower{view(a0, e0), view(a1, e0), view(a1, e1)}, upper{view(a0, e0), view(a0, e1), view(a1, e1)};
        const bool upperSide = glm::dot(d, glm::cross(directions_[lower[0]], directions_[lower[2]])) > 0.0f;
        tryTriangle(upperSide ? upper : lower);
        if (best > kHolds) tryTriangle(upperSide ? lower : upper);
    };
    // The named cell first; its neighbours up and down only when it does not hold the eye.
    tryCell(named);
    if (best > kHolds && named > 0) tryCell(named - 1);
    if (best > kHolds && named + 1 < cells) tryCell(named + 1);
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
