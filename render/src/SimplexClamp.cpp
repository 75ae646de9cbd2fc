#include "throng/render/SimplexClamp.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace throng {
namespace {

// The nearest point of segment [a, b] to p, as the parameter along it (0 at a, 1 at b).
float alongSegment(const glm::vec3& a, const glm::vec3& b, const glm::vec3& p) {
    const glm::vec3 ab = b - a;
    const float length2 = glm::dot(ab, ab);
    return length2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / length2, 0.0f, 1.0f) : 0.0f;
}

}  // namespace

std::array<float, 3> clampedBarycentric(const std::array<glm::vec3, 3>& corners, const glm::vec3& point) {
    const glm::vec3 &a = corners[0], &b = corners[1], &c = corners[2];
    const glm::vec3 ab = b - a, ac = c - a;
    const glm::vec3 normal = glm::cross(ab, ac);
    const float area2 = glm::dot(normal, normal);
    const float scale2 = std::max({glm::dot(ab, ab), glm::dot(ac, ac), glm::dot(c - b, c - b)});
    if (!(area2 > 1e-12f * scale2 * scale2)) {
        // Degenerate: the nearest point of the three sides.
        std::array<float, 3> best{1.0f, 0.0f, 0.0f};
        float bestDistance = glm::dot(point - a, point - a);
        const int sides[3][2] = {{0, 1}, {1, 2}, {0, 2}};
        for (const auto& s : sides) {
            const float t = alongSegment(corners[s[0]], corners[s[1]], point);
            const glm::vec3 q = corners[s[0]] + t * (corners[s[1]] - corners[s[0]]);
            const float d = glm::dot(point - q, point - q);
            if (d < bestDistance) {
                bestDistance = d;
                best = {0.0f, 0.0f, 0.0f};
                best[s[0]] = 1.0f - t;
                best[s[1]] = t;
            }
        }
        return best;
    }
    // Which of the triangle's seven regions (inside, beyond an edge, beyond a corner) the point's
    // projection lies in, from its products with the two sides at each corner (Ericson,
    // "Real-Time Collision Detection", 5.1.5).
    const glm::vec3 ap = point - a, bp = point - b, cp = point - c;
    const float abap = glm::dot(ab, ap), acap = glm::dot(ac, ap);
    if (abap <= 0.0f && acap <= 0.0f) return {1.0f, 0.0f, 0.0f};  // beyond corner a
    const float abbp = glm::dot(ab, bp), acbp = glm::dot(ac, bp);
    if (abbp >= 0.0f && acbp <= abbp) return {0.0f, 1.0f, 0.0f};  // beyond corner b
    const float abcp = glm::dot(ab, cp), accp = glm::dot(ac, cp);
    if (accp >= 0.0f && abcp <= accp) return {0.0f, 0.0f, 1.0f};  // beyond corner c
    const float nearC = abap * acbp - abbp * acap;  // <= 0: beyond edge ab
    if (nearC <= 0.0f && abap >= 0.0f && abbp <= 0.0f) {
        const float t = abap / (abap - abbp);
        return {1.0f - t, t, 0.0f};
    }
    const float nearB = abcp * acap - abap * accp;  // <= 0: beyond edge ac
    if (nearB <= 0.0f && acap >= 0.0f && accp <= 0.0f) {
        const float t = acap / (acap - accp);
        return {1.0f - t, 0.0f, t};
    }
    const float nearA = abbp * accp - abcp * acbp;  // <= 0: beyond edge bc
    if (nearA <= 0.0f && acbp - abbp >= 0.0f && abcp - accp >= 0.0f) {
        const float t = (acbp - abbp) / ((acbp - abbp) + (abcp - accp));
        return {0.0f, 1.0f - t, t};
    }
    // Inside: the projection's own coordinates (each of nearA, nearB, nearC is a sub-triangle's
    // signed area, times the whole's).
    const float sum = nearA + nearB + nearC;
    const float v = nearB / sum, w = nearC / sum;
    return {std::max(0.0f, 1.0f - v - w), v, w};
}

}  // namespace throng
