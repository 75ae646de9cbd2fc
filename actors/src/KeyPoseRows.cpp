#include "throng/actors/KeyPoseRows.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace throng {

KeyPoseRows::KeyPoseRows(std::uint32_t rows, std::uint32_t poseCount)
    : poseRow_(poseCount, kNone), rowPose_(rows, kNone), rowUsed_(rows, 0), wantedNow_(rows, 0), poseSeen_(poseCount, 0) {
    if (rows == 0) throw std::invalid_argument("KeyPoseRows: a cache needs at least one row");
}

std::uint32_t KeyPoseRows::hold(std::span<const std::uint32_t> wanted, std::uint64_t frame) {
    if (wanted.size() > rowPose_.size())
        throw std::invalid_argument("KeyPoseRows::hold: " + std::to_string(wanted.size()) + " poses wanted but the cache has " +
                                    std::to_string(rowPose_.size()) + " rows");
    for (const std::uint32_t p : wanted)
        if (p >= poseRow_.size())
            throw std::invalid_argument("KeyPoseRows::hold: pose " + std::to_string(p) + " is out of range (the cache knows " +
                                        std::to_string(poseRow_.size()) + " poses)");
    // Duplicates found with per-pose marks (no copy to sort), cleared again before returning or throwing.
    std::uint32_t twice = kNone;
    for (const std::uint32_t p : wanted) {
        if (poseSeen_[p]) twice = p;
        poseSeen_[p] = 1;
    }
    for (const std::uint32_t p : wanted) poseSeen_[p] = 0;
    if (twice != kNone) throw std::invalid_argument("KeyPoseRows::hold: pose " + std::to_string(twice) + " is wanted twice");
    std::fill(wantedNow_.begin(), wantedNow_.end(), std::uint8_t{0});
    for (const std::uint32_t p : wanted)
        if (poseRow_[p] != kNone) {
            wantedNow_[poseRow_[p]] = 1;
            rowUsed_[poseRow_[p]] = frame;
        }
    std::uint32_t updates = 0;
    for (const std::uint32_t p : wanted) {
        if (poseRow_[p] != kNone) continue;
        // An empty row first, else the least recently used row not wanted now (lowest index on ties).
        std::uint32_t victim = kNone;
        for (std::uint32_t r = 0; r < rowPose_.size(); ++r) {
            if (wantedNow_[r]) continue;
            if (rowPose_[r] == kNone) {
                victim = r;
                break;
            }
            if (victim == kNone || rowUsed_[r] < rowUsed_[victim]) victim = r;
        }
        if (rowPose_[victim] != kNone) poseRow_[rowPose_[victim]] = kNone;
        rowPose_[victim] = p;
        poseRow_[p] = victim;
        rowUsed_[victim] = frame;
        wantedNow_[victim] = 1;
        ++updates;
    }
    return updates;
}

void KeyPoseRows::touch(std::uint32_t pose, std::uint64_t frame) {
    const std::uint32_t r = rowOf(pose);
    if (r != kNone) rowUsed_[r] = frame;
}

std::vector<std::uint32_t> KeyPoseRows::held() const {
    std::vector<std::uint32_t> poses;
    held(poses);
    return poses;
}

void KeyPoseRows::held(std::vector<std::uint32_t>& poses) const {
    poses.clear();
    for (const std::uint32_t p : rowPose_)
        if (p != kNone) poses.push_back(p);
}

void KeyPoseRows::copyRows(std::span<const std::uint32_t> poses) {
    if (poses.size() != rowPose_.size())
        throw std::invalid_argument("KeyPoseRows::copyRows: " + std::to_string(poses.size()) + " poses for " + std::to_string(rowPose_.size()) +
                                    " rows");
    for (std::size_t r = 0; r < poses.size(); ++r) {
        const std::uint32_t p = poses[r];
        if (p == kNone) continue;
        const bool twice = p < poseSeen_.size() && poseSeen_[p];
        if (p >= poseRow_.size() || twice) {
            for (std::size_t q = 0; q < r; ++q)
                if (poses[q] != kNone) poseSeen_[poses[q]] = 0;  // all 0 between calls
            throw std::invalid_argument("KeyPoseRows::copyRows: row " + std::to_string(r) + " holds pose " + std::to_string(p) +
                                        (twice ? ", which an earlier row holds" : ", out of range (the cache knows " + std::to_string(poseRow_.size()) + " poses)"));
        }
        poseSeen_[p] = 1;
    }
    std::fill(poseRow_.begin(), poseRow_.end(), kNone);
    for (std::size_t r = 0; r < poses.size(); ++r) {
        rowPose_[r] = poses[r];
        if (poses[r] != kNone) poseRow_[poses[r]] = static_cast<std::uint32_t>(r), poseSeen_[poses[r]] = 0;
    }
}

void KeyPoseRows::clear() {
    std::fill(poseRow_.begin(), poseRow_.end(), kNone);
    std::fill(rowPose_.begin(), rowPose_.end(), kNone);
    std::fill(rowUsed_.begin(), rowUsed_.end(), std::uint64_t{0});
}

}  // namespace throng
