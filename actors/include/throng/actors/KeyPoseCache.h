#pragma once
// The key-pose cache of one template (seed 004): each clip of the template sampled at a fixed rate
// gives its key-poses, whose skin palettes are computed once, at construction (so actors clamped
// to a key-pose share one pose evaluation, and DRAW can skin a missing pose from any thread); a
// fixed number of rows holds skinned key-poses across frames (KeyPoseRows), chosen each frame by
// ActorProcessor from what the actors in the cache's band need (KeyPoseSelection). The renderer
// keeps the skinned rows; this object is the CPU side and the KeyPoseSource the draw list names.
// One cache serves one ActorProcessor: its rows are that processor's state.

#include <cstdint>
#include <memory>
#include <vector>

#include "throng/actors/KeyPoseRows.h"
#include "throng/actors/KeyPoseSelection.h"
#include "throng/scenegraph/KeyPoseSource.h"

namespace throng {

class ActorTemplate;

/// How actors are drawn from the cache.
enum class KeyPoseMode : std::uint8_t {
    Intermittent,   ///< each actor shows its nearest key-pose (§3)
    Interpolative,  ///< each actor blends the two key-poses enclosing its clip time (§4)
};

/// What a KeyPoseCache holds.
struct KeyPoseCacheSettings {
    std::uint32_t rows = 64;           ///< skinned key-poses held at once (> 0)
    KeyPoseMode mode = KeyPoseMode::Intermittent;  ///< how actors use them
    double keyPosesPerSecond = 15.0;   ///< key-poses per second of clip (the seed's 15; > 0)
};

/// The key-poses an actor shows at one clip time.
struct KeyPoseSample {
    std::uint32_t a = 0;   ///< first key-pose
    std::uint32_t b = 0;   ///< second key-pose (== a in intermittent mode)
    float blend = 0.0f;    ///< weight of b
};

/// Key-poses of one template and the rows of their cache.
class KeyPoseCache final : public KeyPoseSource {
public:
    /// The cache of `tmpl`'s key-poses. Throws std::invalid_argument naming the template if it is
    /// null, has no clip, is not drawn by skinned actor-level geometry alone (rigid parts cannot
    /// come from a cache), or a setting is out of range.
    KeyPoseCache(std::shared_ptr<const ActorTemplate> tmpl, const KeyPoseCacheSettings& settings);

    /// The template.
    const ActorTemplate& actorTemplate() const { return *tmpl_; }
    /// The settings.
    const KeyPoseCacheSettings& settings() const { return settings_; }
    /// First key-pose of clip `clip` (its key-poses are consecutive).
    std::uint32_t firstPose(int clip) const { return first_[static_cast<std::size_t>(clip)]; }
    /// Number of key-poses of clip `clip` (at least 1).
    std::uint32_t posesOf(int clip) const { return count_[static_cast<std::size_t>(clip)]; }
    /// Clip of key-pose `pose`.
    int clipOf(std::uint32_t pose) const { return clipOf_[pose]; }
    /// Seconds into its clip of key-pose `pose`.
    double timeOf(std::uint32_t pose) const;
    /// The key-poses an actor playing clip `clip` (looping) shows at `clipTime`, in the cache's
    /// mode. Throws std::out_of_range for a bad clip; a non-finite time gives the clip's first pose.
    KeyPoseSample sample(int clip, double clipTime) const;
    /// The rows: which pose each holds (ActorProcessor updates them every frame).
    KeyPoseRows& rows() { return rows_; }
    /// The rows, read-only.
    const KeyPoseRows& rows() const { return rows_; }
    /// What the actors in the band needed in the last frame (ActorProcessor records it each frame),
    /// for inspection and for measuring the selection against the optimum.
    std::span<const KeyPoseDemand> lastDemand() const { return lastDemand_; }
    /// Records a frame's demand (ActorProcessor does, before choosing the poses).
    void recordDemand(std::span<const KeyPoseDemand> demand) { lastDemand_.assign(demand.begin(), demand.end()); }
    /// Bytes of the palettes computed at construction.
    std::size_t paletteBytes() const { return palettes_.size() * sizeof(glm::mat4); }

    std::uint32_t rowCount() const override { return rows_.rowCount(); }
    std::uint32_t poseCount() const override { return static_cast<std::uint32_t>(clipOf_.size()); }
    std::span<const glm::mat4> palette(std::uint32_t skin, std::uint32_t pose) const override;

private:
    std::shared_ptr<const ActorTemplate> tmpl_;
    KeyPoseCacheSettings settings_;
    std::vector<std::uint32_t> first_, count_;  // per clip
    std::vector<int> clipOf_;                   // per pose
    std::vector<std::size_t> skinBase_;         // per skin: first matrix of its pose 0
    std::vector<glm::mat4> palettes_;           // skin by skin, pose by pose
    KeyPoseRows rows_;
    std::vector<KeyPoseDemand> lastDemand_;
};

}  // namespace throng
