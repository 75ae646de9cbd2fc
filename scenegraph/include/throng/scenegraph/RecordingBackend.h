#pragma once
// A DrawBackend that draws nothing and records what it was asked to draw, for tests and for
// comparing two processing methods on the same scene.

#include <cstdint>
#include <string>
#include <vector>

#include "throng/scenegraph/DrawBackend.h"
#include "throng/scenegraph/Math.h"

namespace throng {

class Drawable;
class Node;

/// Records frames as lists of (drawable, node, part, matrix).
class RecordingBackend : public DrawBackend {
public:
    /// One recorded draw.
    struct Record {
        const Drawable* drawable = nullptr;  ///< what was drawn
        const Node* node = nullptr;          ///< the node that produced it
        std::uint32_t instance = 0;          ///< instance within the node
        std::uint32_t part = 0;              ///< part within the instance
        std::uint32_t lodLevel = 0;          ///< level of detail
        Mat4 worldMatrix{1.0};               ///< copy of the model matrix
    };

    void beginFrame(const Camera& camera) override;
    void draw(const DrawList& list) override;
    void endFrame() override;

    /// Records of the last frame.
    const std::vector<Record>& records() const { return records_; }
    /// Number of frames begun.
    std::uint64_t frameCount() const { return frames_; }
    /// Number of draw() calls in the last frame.
    std::uint64_t drawCallsLastFrame() const { return drawCalls_; }
    /// Total primitives of the last frame.
    std::uint64_t primitivesLastFrame() const { return primitives_; }

private:
    std::vector<Record> records_;
    std::uint64_t frames_ = 0;
    std::uint64_t drawCalls_ = 0;
    std::uint64_t primitives_ = 0;
};

}  // namespace throng
