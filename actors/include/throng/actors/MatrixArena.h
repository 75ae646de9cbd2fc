#pragma once
// Storage for the matrices a frame's draw items point to: addresses stay valid until clear(), and
// memory is reused from frame to frame (no allocation once warmed up).

#include <memory>
#include <vector>

#include "throng/scenegraph/Math.h"

namespace throng {

/// Chunked, address-stable storage of matrices.
class MatrixArena {
public:
    /// Stores `m` and returns its stable address.
    const Mat4* push(const Mat4& m) {
        if (used_ == kChunk * chunks_.size() ) chunks_.push_back(std::make_unique<Mat4[]>(kChunk));
        Mat4* slot = &chunks_[used_ / kChunk][used_ % kChunk];
        *slot = m;
        ++used_;
        return slot;
    }
    /// Forgets every matrix (keeps the memory).
    void clear() { used_ = 0; }
    /// Number of matrices stored.
    std::size_t size() const { return used_; }

private:
    static constexpr std::size_t kChunk = 4096;
    std::vector<std::unique_ptr<Mat4[]>> chunks_;
    std::size_t used_ = 0;
};

}  // namespace throng
