#pragma once
// Optimal reciprocal collision avoidance (ORCA), after van den Berg, Guy, Lin and Manocha, "Reciprocal
// n-body collision avoidance" (2011): each neighbour excludes a half-plane of velocities (the agent
// taking half the responsibility of avoiding it within a time horizon), and the agent takes the
// velocity nearest its preferred one inside all half-planes and its speed limit: a 2-D linear
// program. When the half-planes leave nothing (a crowd too dense), the velocity that enters the
// deepest of them least is taken (the paper's 3-D program).
//
// Exactly symmetric encounters (two walkers head-on on one line) stall: each only slows for the
// other. Callers turn preferred velocities by a small amount that differs between walkers, as
// ORCA's authors do.
//
// Plain functions on the ground plane (x, z as a 2-D vector), no state, no allocation: the stepper
// that uses them owns the neighbour lists and the lines' storage.

#include <span>

#include <glm/vec2.hpp>

namespace throng::sim::orca {

/// A half-plane of allowed velocities: those on the left of `direction` through `point`.
struct Line {
    glm::vec2 point{0.0f};      ///< a velocity on the boundary, m/s
    glm::vec2 direction{0.0f};  ///< unit vector along the boundary; allowed velocities lie to its left
};

/// An agent as its neighbours see it.
struct Body {
    glm::vec2 position{0.0f};  ///< metres
    glm::vec2 velocity{0.0f};  ///< m/s
    float radius = 0.0f;       ///< metres
};

/// The half-plane of velocities by which `self` avoids `other` for `horizon` seconds, taking `share`
/// of the change needed (0.5: reciprocal, each does half; 1: `self` does it all, as when `other` has
/// the right of way); when they already overlap, resolved within one step of `dt` seconds.
Line agentLine(const Body& self, const Body& other, float horizon, float dt, float share = 0.5f);

/// The half-plane of velocities by which `self` keeps clear of the wall segment from `a` to `b`, whose
/// free side is the one (-d.y, d.x) points away from, d = b - a (Detour's winding of a navigation
/// mesh's boundary edges, x and z on the ground as x and y), for `horizon` seconds; when it
/// already reaches into the wall, out of it within one step of `dt` seconds. Only the velocity
/// across the wall is limited, sliding along it is not. False (and `line` untouched) when the wall
/// does not face the walker: it stands beyond the segment's ends or behind it.
bool wallLine(const Body& self, glm::vec2 a, glm::vec2 b, float horizon, float dt, Line& line);

/// The velocity nearest `preferred` inside every line and within `maxSpeed`. When no velocity
/// satisfies all of them, the lines from `firstSoft` on are relaxed together (the first ones, such as
/// walls, stay hard as far as possible) and the velocity that enters the deepest of those least is
/// returned; when the first ones cannot all be met within `maxSpeed` either, every line is relaxed.
/// `scratch` holds at least lines.size() lines (used only then).
glm::vec2 solve(std::span<const Line> lines, std::size_t firstSoft, glm::vec2 preferred, float maxSpeed, std::span<Line> scratch);

}  // namespace throng::sim::orca
