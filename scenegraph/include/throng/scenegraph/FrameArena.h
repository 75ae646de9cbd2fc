#pragma once
// Storage for what a frame's draw items point to (model matrices, skin palettes): addresses stay
// valid until clear(), and memory is reused from frame to frame. An arena that needed several
// blocks in a frame is merged into one block of their total size when it is cleared, so once warm
// it holds one block that every later frame of the same size fills without allocating or faulting.

#include <algorithm>
#include <memory>
#include <vector>

namespace throng {

/// Chunked, address-stable storage of T.
template <class T>
class FrameArena {
public:
    /// Stores `value` and returns its stable address.
    const T* push(const T& value) {
        T* slot = allocate(1);
        *slot = value;
        return slot;
    }
    /// Room for `n` consecutive values, valid until clear().
    T* allocate(std::size_t n) {
        while (current_ < chunks_.size() && chunks_[current_].size - chunks_[current_].used < n) ++current_;
        if (current_ == chunks_.size()) {
            // Blocks grow geometrically: small lists stay small, large ones need few blocks.
            const std::size_t size = std::max(n, chunks_.empty() ? kFirstChunk : 2 * chunks_.back().size);
            chunks_.push_back(Chunk{std::make_unique_for_overwrite<T[]>(size), size, 0});  // written before read: no zeroing
        }
        Chunk& c = chunks_[current_];
        T* out = c.data.get() + c.used;
        c.used += n;
        size_ += n;
        return out;
    }
    /// Forgets every value. Keeps the memory: merged into one block when it was spread over several.
    void clear() {
        if (chunks_.size() > 1) {
            std::size_t total = 0;
            for (const Chunk& c : chunks_) total += c.size;
            chunks_.clear();
            chunks_.push_back(Chunk{std::make_unique_for_overwrite<T[]>(total), total, 0});
        }
        for (Chunk& c : chunks_) c.used = 0;
        current_ = 0;
        size_ = 0;
    }
    /// Number of values stored.
    std::size_t size() const { return size_; }

private:
    static constexpr std::size_t kFirstChunk = 64;
    struct Chunk {
        std::unique_ptr<T[]> data;
        std::size_t size = 0;
        std::size_t used = 0;
    };
    std::vector<Chunk> chunks_;
    std::size_t current_ = 0;
    std::size_t size_ = 0;
};

}  // namespace throng
