#pragma once
// The occlusion stage of a frame: gathers the Occluder nodes of a scene that lie in the frustum,
// draws the nearest into an OcclusionBuffer and finishes it, so that CULL (generic nodes) and the
// actor cascade (Refpoint and Sklsroot spheres) can reject what the occluders hide. A processor
// owns one only when the scene asks for occlusion: a scene without it builds and pays nothing.
// Optionally the stage rests: after a frame whose tests rejected little (a view over the roofs), it
// builds nothing and tests nothing for a few frames, until the camera moves or turns. Resting only
// ever rejects less, so it stays conservative; what it costs is the hidden actors posed meanwhile.

#include <cstdint>
#include <vector>

#include "throng/scenegraph/Frustum.h"
#include "throng/scenegraph/OcclusionBuffer.h"

namespace throng {

class Camera;
class Node;
class Occluder;

/// What the occlusion stage may spend.
struct OcclusionSettings {
    int width = 256;          ///< buffer width in pixels (the resolution knob), [8, 4096]
    int height = 144;         ///< buffer height in pixels, [8, 4096]
    int maxOccluders = 128;   ///< nearest Occluder nodes drawn per frame, >= 1
    /// Frames without occlusion after a frame whose tests rejected little, [0, 1000]; 0: never rest.
    int restFrames = 0;
    /// "Little": objects rejected per object tested below this share, [0, 1].
    double restBelow = 0.1;
    /// A rest ends early once the eye moved this far (metres) from where the little was measured...
    double wakeDistance = 2.0;
    /// ...or the view direction turned by this many degrees, [0, 180].
    double wakeAngleDegrees = 10.0;
};

/// What the occlusion stage did in one frame.
struct OcclusionStatistics {
    std::uint64_t occludersInView = 0;     ///< Occluder nodes in the frustum
    std::uint64_t occludersDrawn = 0;      ///< of those, drawn (the nearest, eye outside their shell)
    std::uint64_t occludersInsideShell = 0;///< left out because the eye was inside their shell
    std::uint64_t boxesDrawn = 0;          ///< boxes that wrote pixels
    std::uint64_t pixelsWritten = 0;       ///< buffer pixels written
    double bufferMs = 0;                   ///< gathering, drawing and the pyramid
    bool rested = false;                   ///< the stage rested: no buffer, no tests this frame
};

/// Builds one frame's occlusion buffer from a scene's Occluder nodes.
class OcclusionCulling {
public:
    /// A stage with `settings`; throws std::invalid_argument naming a bad setting.
    explicit OcclusionCulling(const OcclusionSettings& settings = {});

    /// Gathers the occluders of `root` (world matrices and bounds up to date) inside `frustum`,
    /// draws the nearest for `camera` and finishes the buffer.
    const OcclusionStatistics& build(Node& root, const Camera& camera, const Frustum& frustum);

    /// Whether this frame should build and test: false while resting, and then statistics() says
    /// so. A rest ends when its frames are spent or `camera` moved or turned past the wake limits.
    bool due(const Camera& camera);
    /// After a frame that built the buffer: `rejected` objects (actors and nodes) of `tested`
    /// objects tested. Below the settings' share, the next restFrames frames rest.
    void settle(std::uint64_t rejected, std::uint64_t tested);

    /// The buffer of the last build().
    const OcclusionBuffer& buffer() const { return buffer_; }
    /// Statistics of the last build().
    const OcclusionStatistics& statistics() const { return stats_; }
    /// The settings.
    const OcclusionSettings& settings() const { return settings_; }

private:
    struct Candidate {
        double distance;
        const Occluder* occluder;
    };
    OcclusionSettings settings_;
    OcclusionBuffer buffer_;
    OcclusionStatistics stats_;
    std::vector<const Occluder*> found_;
    std::vector<Candidate> candidates_;
    int restLeft_ = 0;        // frames still to rest
    bool builtThisFrame_ = false;
    Vec3 measuredEye_{0.0};   // where the last built frame was seen from
    Vec3 measuredView_{0.0};  // and its view direction
};

}  // namespace throng
