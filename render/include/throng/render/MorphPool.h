#pragma once
// Which morphed impostor cells of one atlas are resident, and which new ones a frame may make
// (DESIGN.md, Impostors). A fixed number of slots (texture layers the renderer owns) holds cells
// across frames; each frame the cells its impostors want are counted, the resident ones are kept,
// and at most `budget` new ones are made, the most wanted first, in slots no impostor of this
// frame uses (least recently used first). A wanted cell that is neither resident nor made shows
// its nearest stored key-frame instead. No GL here and no allocation once warm: flat arrays over
// the atlas's (key-frame, view) cells.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace throng {

/// A cell to make this frame: morph (key-frame, view) of the atlas into `slot`.
struct MorphFill {
    std::uint32_t view = 0;  ///< view of the cell
    int keyframe = 0;        ///< dropped key-frame of the cell
    int slot = 0;            ///< slot (texture layer of the pool) to write
};

/// What a MorphPool did in the current frame.
struct MorphPoolStatistics {
    std::uint64_t wanted = 0;    ///< distinct dropped cells the frame's impostors want
    std::uint64_t resident = 0;  ///< of those, already made in an earlier frame
    std::uint64_t made = 0;      ///< new cells chosen this frame (fills)
    std::uint64_t deferred = 0;  ///< wanted cells left out by the budget or the slots: shown as a stored key-frame
    std::uint64_t evicted = 0;   ///< resident cells whose slot was given to a new one
};

/// Resident morphed cells of one atlas, with a per-frame budget for new ones.
class MorphPool {
public:
    /// A pool of `slots` cells for an atlas of `keyframes` x `views` cells. Throws
    /// std::invalid_argument if a count is negative or the atlas is empty.
    MorphPool(int slots, int keyframes, std::uint32_t views);

    /// Starts a frame: forgets the previous frame's wants (resident cells stay).
    void beginFrame();
    /// Counts one use of dropped cell (keyframe, view) by an impostor of this frame. Throws
    /// std::out_of_range for a cell outside the atlas.
    void want(int keyframe, std::uint32_t view);
    /// Chooses this frame's new cells: wanted cells not resident, the highest score (demand
    /// smoothed over frames) first, ties by key-frame then view (deterministic), at most `budget`
    /// of them (negative: no limit), each in an empty slot or in place of the resident cell of
    /// lowest score when the new one's score is over kReplaceMargin times it. Call once per frame,
    /// after every want(); the fills stay valid until the next beginFrame().
    std::span<const MorphFill> resolve(int budget);
    /// The slot holding cell (keyframe, view), or -1 when it is not resident or still being made
    /// (after resolve(): including this frame's fills that are not pending).
    int slotOf(int keyframe, std::uint32_t view) const;
    /// Marks `slot` (a fill of this frame) as being made elsewhere: slotOf() ignores it and no fill
    /// takes it until setReady(). Throws std::out_of_range for a bad slot.
    void setPending(int slot);
    /// Marks a pending `slot` as made. Throws std::out_of_range for a bad slot.
    void setReady(int slot);
    /// Forgets every resident cell (the slots' contents are lost, e.g. with the texture).
    void clear();

    /// Weight of the past in a cell's score: score = kScoreDecay * score + this frame's uses.
    static constexpr float kScoreDecay = 0.9f;
    /// How much more a new cell's score must be to take a resident cell's slot.
    static constexpr float kReplaceMargin = 1.25f;

    /// Number of slots.
    int slots() const { return static_cast<int>(cellOfSlot_.size()); }
    /// Statistics of the current frame.
    const MorphPoolStatistics& statistics() const { return stats_; }

private:
    std::size_t cellIndex(int keyframe, std::uint32_t view) const;

    std::uint32_t views_;
    int keyframes_;
    std::uint64_t frame_ = 0;
    std::vector<int> slotOfCell_;            // per cell: slot or -1
    std::vector<int> cellOfSlot_;            // per slot: cell or -1
    std::vector<std::uint64_t> slotUsed_;    // per slot: last frame it was wanted
    std::vector<std::uint8_t> slotReady_;    // per slot: 0 while its cell is being made
    std::vector<std::uint32_t> demand_;      // per cell: uses this frame
    std::vector<float> score_;               // per cell: uses smoothed over frames
    std::vector<std::uint32_t> wantedCells_; // cells with demand this frame
    std::vector<std::uint32_t> candidates_;  // scratch: wanted cells not resident
    std::vector<int> freeSlots_;             // scratch: slots a fill may take, best first
    std::vector<MorphFill> fills_;
    MorphPoolStatistics stats_;
};

}  // namespace throng
