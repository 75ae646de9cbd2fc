#pragma once
// Draw items of actors as bytes, so that the processes of a run that pose their own actors can
// send the drawing process what to draw rather than the actors' state: each item becomes one
// record (its placement, its palette and morph weights inline, its drawable, node and key-pose
// source by number: DrawReferences.h), and the drawing process merges every process's records
// into the list it draws, in the order one process holding every actor would have made it.
// Messages come from processes of the same build; they are checked all the same (a record that
// does not fit this process's numbering is refused), because a mismatched scene must fail
// clearly, not draw garbage.

#include <cstddef>
#include <span>
#include <vector>

#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/DrawReferences.h"

namespace throng {

/// The most skin matrices a record may carry (a glTF skin of this many joints is far past any
/// character the project loads).
inline constexpr std::uint32_t kMaxRecordPaletteSize = 4096;

/// Appends to `out` one message holding a record of every actor item of `list`, in the list's
/// order (items of no actor, the scene's own geometry, are the drawing process's and are left
/// out). Returns the number of records. Throws std::invalid_argument naming the item whose
/// drawable, node or key-pose source `refs` does not number; `out` is then as it was.
std::size_t writeDrawRecords(const DrawList& list, const DrawReferences& refs, std::vector<std::byte>& out);

/// Merges messages of draw records into a draw list; keeps its scratch between frames.
class DrawRecordMerger {
public:
    /// Appends to `into` the items of every message of `messages` (each from writeDrawRecords, its
    /// records in order of node number, then instance, as a traversal makes them), merged in that
    /// order: the items one process making them all would have listed, each with its drawable's
    /// primitives. Every message is checked before anything is appended: one cut short, a number
    /// `refs` lacks, a representation or key-pose row out of range, morph weights not one per morph
    /// target of the drawable, a palette over kMaxRecordPaletteSize, a number that is not finite,
    /// or records out of order throws std::invalid_argument naming the message and the record, and
    /// `into` is left as it was.
    void merge(std::span<const std::span<const std::byte>> messages, const DrawReferences& refs, DrawList& into);

private:
    struct Entry {
        std::uint64_t key;  // node number << 32 | instance
        std::size_t at;     // offset of its record in the message
    };
    static void index(std::span<const std::byte> bytes, std::size_t m, const DrawReferences& refs, std::vector<Entry>& entries);
    std::vector<std::vector<Entry>> entries_;  // per message, its records in order
    std::vector<std::size_t> next_;            // per message, its next record to append
};

}  // namespace throng
