#pragma once
// Skinned key-poses a renderer may keep in a cache of rows and draw instances from (seed 004): the
// CPU side (actors' KeyPoseCache) decides which pose each row holds and which actors it serves; the
// renderer skins a row again only when the pose its own copy holds differs, so a pose kept across
// frames is skinned once. Scenegraph-level so that DRAW needs nothing of actors.

#include <atomic>
#include <cstdint>
#include <span>

#include <glm/mat4x4.hpp>

namespace throng {

/// The key-poses of one template and the rows of its cache.
class KeyPoseSource {
public:
    KeyPoseSource() : serial_(nextSerial()) {}
    /// A copy is another source: it gets a serial of its own.
    KeyPoseSource(const KeyPoseSource&) : serial_(nextSerial()) {}
    /// Keeps this source's own serial (a copy is another source).
    KeyPoseSource& operator=(const KeyPoseSource&) { return *this; }
    virtual ~KeyPoseSource() = default;
    /// A number no other source of this process has had: a renderer that meets a new source at a
    /// freed one's address tells them apart by it.
    std::uint64_t serial() const { return serial_; }
    /// Rows of the cache: the number of key-poses it holds at once.
    virtual std::uint32_t rowCount() const = 0;
    /// Key-poses the source knows (indices 0 .. poseCount() - 1 over every clip it serves).
    virtual std::uint32_t poseCount() const = 0;
    /// Skin palette (joint to Skeleton Root, times the inverse bind matrix) of skin `skin` in
    /// key-pose `pose`; empty when either index is out of range. Safe to call from any thread.
    virtual std::span<const glm::mat4> palette(std::uint32_t skin, std::uint32_t pose) const = 0;

private:
    static std::uint64_t nextSerial() {
        static std::atomic<std::uint64_t> next{1};
        return next.fetch_add(1, std::memory_order_relaxed);
    }
    std::uint64_t serial_;
};

/// For an item drawn from a key-pose cache (Representation::KeyPose): what its instance shows.
struct KeyPoseRef {
    const KeyPoseSource* source = nullptr;  ///< the poses and the cache they live in
    std::uint32_t skin = 0;                 ///< the skin of the source the item's mesh is bound to
    std::uint32_t pose[2] = {0, 0};         ///< key-poses shown (intermittent: both the same)
    std::uint32_t row[2] = {0, 0};          ///< the cache rows holding them
    float blend = 0.0f;                     ///< weight of pose[1] (0: pose[0] alone)
};

}  // namespace throng
