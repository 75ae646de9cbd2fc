#include "throng/sim/OrcaSolver.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

namespace throng::sim::orca {
namespace {

constexpr float kEpsilon = 1e-5f;

// The 2-D cross product: > 0 when `b` turns left of `a`.
float cross(glm::vec2 a, glm::vec2 b) { return a.x * b.y - a.y * b.x; }

// How far `v` lies outside line `l` (> 0: it violates it).
float outside(const Line& l, glm::vec2 v) { return cross(l.direction, l.point - v); }

// The best velocity on line `i` inside the disc of `radius` and inside lines [0, i): nearest
// `target`, or (byDirection) furthest along the unit vector `target`. False when that segment is empty.
bool onLine(std::span<const Line> lines, std::size_t i, float radius, glm::vec2 target, bool byDirection, glm::vec2& result) {
    const Line& li = lines[i];
    const float along = glm::dot(li.point, li.direction);
    const float discriminant = along * along + radius * radius - glm::dot(li.point, li.point);
    if (discriminant < 0.0f) return false;  // the line misses the disc
    const float root = std::sqrt(discriminant);
    float lo = -along - root, hi = -along + root;
    for (std::size_t j = 0; j < i; ++j) {
        const Line& lj = lines[j];
        const float denominator = cross(li.direction, lj.direction);
        const float numerator = cross(lj.direction, li.point - lj.point);
        if (std::abs(denominator) <= kEpsilon) {  // parallel
            if (numerator < 0.0f) return false;
            continue;
        }
        const float t = numerator / denominator;
        if (denominator >= 0.0f) hi = std::min(hi, t);
        else lo = std::max(lo, t);
        if (lo > hi) return false;
    }
    float t;
    if (byDirection) t = glm::dot(target, li.direction) > 0.0f ? hi : lo;
    else t = std::clamp(glm::dot(li.direction, target - li.point), lo, hi);
    result = li.point + t * li.direction;
    return true;
}

// The 2-D program: lines taken in order, the optimum moved onto each line it violates. Returns the
// number of lines satisfied before one could not be (lines.size() when all are).
std::size_t program2(std::span<const Line> lines, float radius, glm::vec2 target, bool byDirection, glm::vec2& result) {
    if (byDirection) result = target * radius;
    else if (glm::dot(target, target) > radius * radius) result = glm::normalize(target) * radius;
    else result = target;
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (outside(lines[i], result) <= 0.0f) continue;
        const glm::vec2 kept = result;
        if (!onLine(lines, i, radius, target, byDirection, result)) {
            result = kept;
            return i;
        }
    }
    return lines.size();
}

}  // namespace

Line agentLine(const Body& self, const Body& other, float horizon, float dt, float share) {
    const glm::vec2 p = other.position - self.position;
    const glm::vec2 v = self.velocity - other.velocity;
    const float r = self.radius + other.radius;
    const float d2 = glm::dot(p, p);
    Line line;
    glm::vec2 u;
    if (d2 > r * r) {
        // The velocity obstacle: a cone towards the other, cut by a disc of radius r / horizon.
        const glm::vec2 w = v - p / horizon;  // from the cut-off disc's centre
        const float w2 = glm::dot(w, w);
        const float towards = glm::dot(w, p);
        if (towards < 0.0f && towards * towards > r * r * w2) {
            // Nearest boundary point is on the cut-off disc.
            const float wLength = std::sqrt(w2);
            const glm::vec2 unit = w / wLength;
            line.direction = glm::vec2(unit.y, -unit.x);
            u = (r / horizon - wLength) * unit;
        } else {
            // Nearest boundary point is on one of the cone's legs.
            const float leg = std::sqrt(d2 - r * r);
            if (cross(p, w) > 0.0f) line.direction = glm::vec2(p.x * leg - p.y * r, p.x * r + p.y * leg) / d2;
            else line.direction = -glm::vec2(p.x * leg + p.y * r, -p.x * r + p.y * leg) / d2;
            u = glm::dot(v, line.direction) * line.direction - v;
        }
    } else {
        // Already overlapping: apart within this step.
        const glm::vec2 w = v - p / dt;
        const float wLength = std::max(std::sqrt(glm::dot(w, w)), kEpsilon);
        const glm::vec2 unit = w / wLength;
        line.direction = glm::vec2(unit.y, -unit.x);
        u = (r / dt - wLength) * unit;
    }
    line.point = self.velocity + share * u;
    return line;
}

bool wallLine(const Body& self, glm::vec2 a, glm::vec2 b, float horizon, float dt, Line& line) {
    const glm::vec2 ab = b - a;
    const float length = std::sqrt(glm::dot(ab, ab));
    if (length <= kEpsilon) return false;
    const glm::vec2 along = ab / length;
    const glm::vec2 into(-along.y, along.x);  // across the segment, from its free side into the wall
    const float t = glm::dot(self.position - a, along);
    // Beyond its ends the next segment (or the mesh's clamp) takes over: a segment's end is not a
    // post to walk round, or every joint of a straight wall would stop walkers.
    if (t < 0.0f || t > length) return false;
    const float distance = glm::dot(a - self.position, into);  // > 0 on the free side
    if (distance < -self.radius) return false;                 // behind the wall
    const float gap = distance - self.radius;
    const float limit = gap > 0.0f ? gap / horizon : gap / dt;
    line.point = into * limit;
    line.direction = -along;  // allowed velocities (v . into <= limit) lie on its left
    return true;
}

glm::vec2 solve(std::span<const Line> lines, std::size_t firstSoft, glm::vec2 preferred, float maxSpeed, std::span<Line> scratch) {
    glm::vec2 result;
    const std::size_t satisfied = program2(lines, maxSpeed, preferred, false, result);
    if (satisfied == lines.size()) return result;
    // Infeasible: from the first line that failed, minimise how deep the velocity lies in the soft
    // lines, keeping the hard ones (the 3-D program, solved as a 2-D one per violated line). When the
    // hard lines alone cannot be met within the speed limit (a wall that asks for a faster way out
    // than the walker has), every line is soft: the least deep velocity, not none at all.
    const std::size_t hard = satisfied < firstSoft ? 0 : firstSoft;
    float depth = 0.0f;
    for (std::size_t i = std::max(satisfied, hard); i < lines.size(); ++i) {
        if (outside(lines[i], result) <= depth) continue;
        std::size_t n = 0;
        for (std::size_t j = 0; j < hard; ++j) scratch[n++] = lines[j];
        for (std::size_t j = hard; j < i; ++j) {
            // The line of velocities equally deep in lines i and j.
            Line l;
            const float determinant = cross(lines[i].direction, lines[j].direction);
            if (std::abs(determinant) <= kEpsilon) {
                if (glm::dot(lines[i].direction, lines[j].direction) > 0.0f) continue;  // same direction: j adds nothing
                l.point = 0.5f * (lines[i].point + lines[j].point);
            } else {
                l.point = lines[i].point +
                          (cross(lines[j].direction, lines[i].point - lines[j].point) / determinant) * lines[i].direction;
            }
            l.direction = glm::normalize(lines[j].direction - lines[i].direction);
            scratch[n++] = l;
        }
        const glm::vec2 kept = result;
        // Furthest into line i's allowed side, as far as the others let it.
        if (program2(scratch.first(n), maxSpeed, glm::vec2(-lines[i].direction.y, lines[i].direction.x), true, result) < n)
            result = kept;  // rounding: keep what was found
        depth = outside(lines[i], result);
    }
    return result;
}

}  // namespace throng::sim::orca
