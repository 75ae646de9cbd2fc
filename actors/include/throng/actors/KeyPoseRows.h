#pragma once
// The rows of a fixed-size key-pose cache kept from frame to frame (seed 004 §4.2, "retention"):
// a pose already held keeps its row and is not skinned again; a newly wanted pose takes an empty
// row, else the row of the least recently used pose that is not wanted this frame. Poses held but
// not wanted stay until their row is needed, so they go on serving actors for free.

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

namespace throng {

/// Which key-pose each row of a cache holds.
class KeyPoseRows {
public:
    /// Marks a row or a pose with nothing assigned.
    static constexpr std::uint32_t kNone = ~std::uint32_t{0};

    /// `rows` empty rows for poses 0 .. poseCount - 1. Throws std::invalid_argument if rows is 0.
    KeyPoseRows(std::uint32_t rows, std::uint32_t poseCount);

    /// Makes every pose of `wanted` (distinct, at most rowCount(), each below poseCount()) held,
    /// marking them used in `frame`; returns how many were not held before (the cache updates, each
    /// one skinning). Throws std::invalid_argument for a bad pose or too many poses.
    std::uint32_t hold(std::span<const std::uint32_t> wanted, std::uint64_t frame);
    /// Marks held pose `pose` used in `frame` (it serves an actor without being wanted).
    void touch(std::uint32_t pose, std::uint64_t frame);

    /// Row holding `pose`, or kNone.
    std::uint32_t rowOf(std::uint32_t pose) const { return pose < poseRow_.size() ? poseRow_[pose] : kNone; }
    /// Pose held in `row`, or kNone.
    std::uint32_t poseIn(std::uint32_t row) const { return row < rowPose_.size() ? rowPose_[row] : kNone; }
    /// Number of rows.
    std::uint32_t rowCount() const { return static_cast<std::uint32_t>(rowPose_.size()); }
    /// Number of poses the rows may hold.
    std::uint32_t poseCount() const { return static_cast<std::uint32_t>(poseRow_.size()); }
    /// Poses currently held, in row order.
    std::vector<std::uint32_t> held() const;
    /// Writes the poses currently held, in row order, into `poses` (emptied first; its memory kept).
    void held(std::vector<std::uint32_t>& poses) const;
    /// Number of rows holding a pose.
    std::uint32_t heldCount() const {
        return static_cast<std::uint32_t>(rowPose_.size() - static_cast<std::size_t>(std::count(rowPose_.begin(), rowPose_.end(), kNone)));
    }
    /// The pose each row holds (kNone: empty), in row order.
    std::span<const std::uint32_t> rowPoses() const { return rowPose_; }
    /// Makes row r hold poses[r] (kNone: empty), as another process's rows of the same cache do
    /// (rowPoses() there). When the poses were last used is not copied: a process whose rows follow
    /// another's does not select (KeyPoseArbiter). Throws std::invalid_argument, the rows unchanged,
    /// unless there is one pose per row, each below poseCount() or kNone, none twice.
    void copyRows(std::span<const std::uint32_t> poses);
    /// Empties every row.
    void clear();

private:
    std::vector<std::uint32_t> poseRow_;   // per pose: its row or kNone
    std::vector<std::uint32_t> rowPose_;   // per row: its pose or kNone
    std::vector<std::uint64_t> rowUsed_;   // per row: last frame its pose was used
    std::vector<std::uint8_t> wantedNow_;  // scratch: per row, wanted in the current hold()
    std::vector<std::uint8_t> poseSeen_;   // scratch: per pose, met in `wanted` (all 0 between calls)
};

}  // namespace throng
