#pragma once
// The baked viewpoints of an impostor: orthographic views on a hemisphere around the actor,
// `azimuths` around +Y times `elevations` rings from the horizon up (seed 000 §3: 16 x 4). Views are
// numbered ring by ring: view = ring * azimuths + azimuth. Blending (seed 003 §4.1-4.2): each cell of
// the (azimuth, elevation) grid splits into two triangles of three views (a simplex on the
// hemisphere); the eye's barycentric coordinates in the triangle nearest it, clamped to that
// triangle (SimplexClamp: against its sides and corners, not weight by weight), optionally
// modulated by a quintic smoothstep and renormalised, replace snapping to the nearest view.

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace throng {

/// Three views and their weights (summing to 1); unused entries have weight 0.
struct ViewBlend {
    std::array<std::uint32_t, 3> views{0, 0, 0};  ///< view indices
    std::array<float, 3> weights{1.0f, 0.0f, 0.0f};  ///< barycentric weights, >= 0, sum 1
};

/// A grid of viewpoints on the upper hemisphere, in the actor's frame (Y up, the actor facing +Z).
class ViewHemisphere {
public:
    /// `azimuths` (>= 3) views around, `elevations` (>= 1) rings from 0 up to `topElevation`
    /// radians (in [0, pi/2]; the rings are evenly spaced, the first on the horizon). Throws
    /// std::invalid_argument for values out of range.
    ViewHemisphere(int azimuths = 16, int elevations = 4, float topElevation = 1.1780972f);

    /// Views around.
    int azimuths() const { return azimuths_; }
    /// Rings.
    int elevations() const { return elevations_; }
    /// Number of views (azimuths * elevations).
    std::uint32_t viewCount() const { return static_cast<std::uint32_t>(azimuths_ * elevations_); }
    /// Azimuth of view column `a` (radians about +Y, 0 looking from +Z).
    float azimuth(int a) const;
    /// Elevation of ring `e` (radians above the horizon).
    float elevation(int e) const;
    /// Unit direction from the actor towards the eye of view `view`. Throws std::out_of_range for a
    /// view beyond viewCount().
    glm::vec3 direction(std::uint32_t view) const;
    /// The view whose direction is nearest `toEye` (actor frame; need not be normalised).
    std::uint32_t nearest(const glm::vec3& toEye) const;
    /// The three views of the triangle holding `toEye` (actor frame; need not be normalised) with the
    /// barycentric weights of the eye's ray through the triangle's plane. An eye outside every
    /// triangle (above the top ring, below the horizon) takes the triangle whose nearest point is
    /// nearest it, and that point's weights (clamped to the triangle, seed 003 §4.1.2): only the
    /// views of a side or a corner, never an extrapolation. With `smoothstep`, each weight goes
    /// through 6x^5 - 15x^4 + 10x^3 and the weights are renormalised (sharper, seed 003). A zero or
    /// non-finite direction gives view 0.
    ViewBlend blend(const glm::vec3& toEye, bool smoothstep = false) const;

private:
    int azimuths_;
    int elevations_;
    float top_;
    std::vector<glm::vec3> directions_;  // each view's, computed once
};

}  // namespace throng
