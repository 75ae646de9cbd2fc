#pragma once
// How the cascade's jobs run their per-actor loops: in fixed chunks, in parallel on the threads of
// the enclosing ThreadTeam::run(), each chunk with an output of its own (counts, FMULT tallies,
// draw items) joined into the frame's in chunk order, so results do not depend on the number of
// threads. One PhaseLoop serves every job of a frame; its chunk outputs are reused from frame to
// frame, so a warm frame allocates nothing.

#include <cstddef>
#include <vector>

#include "throng/actors/ActorFrameStatistics.h"
#include "throng/actors/cascade/CascadeTypes.h"
#include "throng/actors/detail/PoseBatch.h"
#include "throng/scenegraph/BoundingSphere.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/OpCounter.h"
#include "throng/scenegraph/ThreadTeam.h"

namespace throng::cascade {

/// What one chunk of a parallel loop produced.
struct ChunkOutput {
    ActorFrameStatistics counts;      ///< counters only (no times)
    OpCounter ops;                    ///< FMULT tallies, enabled when the frame counts
    DrawSegment* items = nullptr;     ///< where its draw items go (drawing loops): its own segment of the list
    BoundingSphere bound;             ///< a group's bound, merged from its chunk's Refpoint Bspheres
    detail::PoseBatchWorkspace pose;  ///< scratch of the pose batches (phase 5)
};

/// Adds the counters (not the times) of `from` to `into`.
void addCounts(ActorFrameStatistics& into, const ActorFrameStatistics& from);

/// The chunked loops of one frame, and where their counts, tallies and draw items go.
class PhaseLoop {
public:
    /// Loops whose counts go to `stats`, whose FMULT tallies go to `counter` (null: not counting)
    /// and whose draw items go to `drawList` (null: the frame draws nothing). Both stay the caller's.
    void begin(ActorFrameStatistics& stats, OpCounter* counter, DrawList* drawList) {
        stats_ = &stats;
        counter_ = counter;
        drawList_ = drawList;
    }
    /// The frame's statistics (serial parts of a job count here directly).
    ActorFrameStatistics& statistics() const { return *stats_; }
    /// The frame's counter, or null when not counting.
    OpCounter* counter() const { return counter_; }
    /// True once begin() has named the frame's statistics.
    bool ready() const { return stats_ != nullptr; }
    /// True when the loop can write draw items.
    bool drawing() const { return drawList_ != nullptr; }

    /// Runs body(out, begin, end) over [0, n) in fixed chunks of `grain`, each with its own
    /// output (counts zeroed, FMULT counter enabled when the frame counts), then adds every
    /// chunk's counts and tallies to the frame's, in chunk order.
    template <class Body>
    void parallel(std::size_t n, std::size_t grain, Body&& body) {
        inChunks(n, grain, false, body);
    }
    /// parallel(), each chunk writing its draw items into a segment of the frame's list of its
    /// own, opened in chunk order: the items are written once, where DRAW reads them.
    template <class Body>
    void parallelDrawing(std::size_t n, std::size_t grain, Body&& body) {
        inChunks(n, grain, true, body);
    }
    /// The output of chunk `c` of the last loop (a job merges what its chunks left there).
    const ChunkOutput& chunk(std::size_t c) const { return chunks_[c]; }
    /// The counter a chunk's work goes to, or null when not counting.
    OpCounter* counterOf(ChunkOutput& out) const { return counter_ ? &out.ops : nullptr; }

private:
    template <class Body>
    void inChunks(std::size_t n, std::size_t grain, bool drawing, Body& body) {
        const std::size_t count = chunkCount(n, grain);
        prepareChunks(count);
        if (drawing) {
            const std::size_t first = drawList_->openSegments(count);
            for (std::size_t c = 0; c < count; ++c) chunks_[c].items = &drawList_->segment(first + c);
        }
        forEachChunk(n, grain, [&](std::size_t c, std::size_t begin, std::size_t end) { body(chunks_[c], begin, end); });
        joinChunks(count);
    }
    void prepareChunks(std::size_t count);
    void joinChunks(std::size_t count);

    ActorFrameStatistics* stats_ = nullptr;
    OpCounter* counter_ = nullptr;
    DrawList* drawList_ = nullptr;
    std::vector<ChunkOutput> chunks_;
};

}  // namespace throng::cascade
