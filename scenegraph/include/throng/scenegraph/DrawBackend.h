#pragma once
// The DRAW stage's interface: a backend receives the camera and the culled draw list each frame.
// The GL renderer implements it; RecordingBackend records calls for tests.

namespace throng {

class Camera;
class DrawList;

/// Something that draws a frame's draw list.
class DrawBackend {
public:
    virtual ~DrawBackend() = default;
    /// Starts a frame seen by `camera`.
    virtual void beginFrame(const Camera& camera) = 0;
    /// Draws every item of `list`, in order.
    virtual void draw(const DrawList& list) = 0;
    /// Finishes the frame (presents it, or reads it back).
    virtual void endFrame() = 0;
    /// One whole frame: beginFrame, draw, endFrame.
    void drawFrame(const Camera& camera, const DrawList& list) {
        beginFrame(camera);
        draw(list);
        endFrame();
    }
};

}  // namespace throng
