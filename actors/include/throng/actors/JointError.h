#pragma once
// Joint-position error between two poses of the same actors: the mean and the largest distance
// between matching joints, in millimetres. Shared by every accuracy measurement that compares
// poses (throng-costmodel's LOD-scale sweep, bench_accuracy's knobs), so they agree on the metric.

#include <algorithm>
#include <cstddef>
#include <span>

#include "throng/scenegraph/Math.h"

namespace throng {

/// Running mean and maximum of joint-position distances (millimetres).
class JointError {
public:
    /// Adds the distances between `positions[j]` and `reference[j]` (metres, world space) for
    /// every j both hold.
    void add(std::span<const Vec3> positions, std::span<const Vec3> reference) {
        const std::size_t n = std::min(positions.size(), reference.size());
        for (std::size_t j = 0; j < n; ++j) addOne(positions[j], reference[j]);
    }
    /// Adds the distance between one joint and its reference (metres).
    void addOne(const Vec3& position, const Vec3& reference) {
        const double e = glm::length(position - reference) * 1000.0;
        sum_ += e;
        max_ = std::max(max_, e);
        ++count_;
    }
    /// Adds another accumulator's joints.
    void merge(const JointError& other) {
        sum_ += other.sum_;
        max_ = std::max(max_, other.max_);
        count_ += other.count_;
    }
    /// Mean distance, mm (0 when no joint was added).
    double meanMm() const { return count_ ? sum_ / double(count_) : 0.0; }
    /// Largest distance, mm.
    double maxMm() const { return max_; }
    /// Joints compared.
    std::size_t count() const { return count_; }

private:
    double sum_ = 0.0, max_ = 0.0;
    std::size_t count_ = 0;
};

}  // namespace throng
