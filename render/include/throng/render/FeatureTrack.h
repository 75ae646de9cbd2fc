#pragma once
// The skeleton behind an impostor's feature lines, in 3-D: each bone's two joints at every key-frame
// (actor frame, as baked), each bone's flesh radius and the limb it belongs to. The features of any
// view follow from it exactly: the lines, their depth toward the eye and their capsule radius in
// pixels, for the baked views and for any eye direction between them (view warping). It costs a few
// floats per bone and key-frame beside megabytes of cells, and needs no hand-picked feature.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "throng/render/BeierNeely.h"

namespace throng {

/// The orthographic camera of an impostor view looking at the baked volume from `toEye`: image x
/// along `right`, image y (up, before the flip to rows) along `up`, depth toward the eye along
/// `toEye`. The baker's cameras (look-at with +Y up) have exactly these axes.
struct ViewBasis {
    glm::vec3 right{1.0f, 0.0f, 0.0f};  ///< image x (pixels grow along it)
    glm::vec3 up{0.0f, 1.0f, 0.0f};     ///< image up (rows grow against it)
    glm::vec3 toEye{0.0f, 0.0f, 1.0f};  ///< unit direction toward the eye (depth grows along it)
};

/// The basis of the view from unit-or-not direction `toEye` (needs a horizontal component; a
/// vertical or non-finite direction throws std::invalid_argument).
ViewBasis viewBasis(const glm::vec3& toEye);

/// Bones of one template and clip in 3-D at every key-frame of an impostor, and what the warp needs
/// to know about each: its flesh radius and its limb.
class FeatureTrack {
public:
    /// A track of `bones` (>= 0) bones over `keyframes` (>= 1) key-frames for cells of `cellSize`
    /// (>= 1) pixels covering the square of half-size `radius` (> 0 metres) around `centre`, as the
    /// baker's views do. Joints start at the centre, radii at 0, every bone its own limb. Throws
    /// std::invalid_argument for values out of range.
    FeatureTrack(std::size_t bones, int keyframes, const glm::vec3& centre, float radius, int cellSize);

    /// Number of bones.
    std::size_t boneCount() const { return nodes_.size(); }
    /// Number of key-frames.
    int keyframeCount() const { return keyframes_; }
    /// Cell side in pixels.
    int cellSize() const { return cellSize_; }
    /// Pixels per metre in every view (orthographic: the same everywhere).
    float pixelsPerMetre() const { return static_cast<float>(cellSize_) / (2.0f * radius_); }

    /// Sets the joints of key-frame `k`: bone i goes from `parents[i]` to `children[i]` (actor frame,
    /// metres). Throws std::invalid_argument for a bad key-frame, sizes or non-finite values.
    void setJoints(int keyframe, std::span<const glm::vec3> parents, std::span<const glm::vec3> children);
    /// Start joint of `bone` at key-frame `k`.
    const glm::vec3& parentJoint(int keyframe, std::size_t bone) const { return joints_[index(keyframe, bone) * 2]; }
    /// End joint of `bone` at key-frame `k`.
    const glm::vec3& childJoint(int keyframe, std::size_t bone) const { return joints_[index(keyframe, bone) * 2 + 1]; }

    /// Flesh radius of each bone (metres).
    const std::vector<float>& radii() const { return radii_; }
    /// Sets the radii (one per bone, finite, >= 0). Throws std::invalid_argument otherwise.
    void setRadii(std::vector<float> radii);
    /// Skeleton nodes each bone joins (parent node, child node): bones sharing a node touch.
    std::span<const std::uint32_t> nodes(std::size_t bone) const { return {&nodes_[bone][0], 2}; }
    /// Limb of each bone: bones of one chain (no branching between them) share a limb id.
    const std::vector<std::uint32_t>& limbs() const { return limbs_; }
    /// Sets the nodes each bone joins and the limbs, one per bone. Throws std::invalid_argument on
    /// a size mismatch.
    void setTopology(std::vector<std::array<std::uint32_t, 2>> nodes, std::vector<std::uint32_t> limbs);
    /// Whether bones `i` and `j` belong together where they meet: one limb, or a shared joint.
    bool related(std::size_t i, std::size_t j) const;

    /// The bones of key-frame `k` projected into the view from `toEye` (pixels of a cell; the
    /// baker's projectBones for baked views).
    std::vector<FeatureLine> lines(int keyframe, const glm::vec3& toEye) const;
    /// Per-line attributes in that view: weight 1, capsule radius in pixels, depth toward the eye
    /// (pixels from the centre).
    std::vector<LineAttributes> attributes(int keyframe, const glm::vec3& toEye) const;
    /// Mean distance (metres) each bone's two joints travel between key-frames `a` and `b`.
    std::vector<float> motion(int a, int b) const;

    /// Bytes of this track (what storing it beside an atlas costs).
    std::size_t bytes() const;

private:
    std::size_t index(int keyframe, std::size_t bone) const;
    glm::vec2 toPixel(const ViewBasis& basis, const glm::vec3& p) const;

    int keyframes_;
    glm::vec3 centre_;
    float radius_;
    int cellSize_;
    std::vector<glm::vec3> joints_;  // [keyframe][bone][parent, child]
    std::vector<float> radii_;
    std::vector<std::array<std::uint32_t, 2>> nodes_;
    std::vector<std::uint32_t> limbs_;
};

}  // namespace throng
