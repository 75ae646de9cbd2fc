#pragma once
// The output of CULL and the input of DRAW: what to draw, where, in traversal order. Items hold
// their transforms, and a list owns copies of the skin palettes its items use, so it describes its frame
// completely: DRAW may render it while the next frame is stepped and culled (Performer's
// multiprocess mode), and nothing at draw time needs to look back into the scene or the crowd.
//
// A list is a sequence of segments. Writers that work apart (the chunks of a parallel loop) each
// fill a segment of their own, opened in the order their items must appear, so their items are
// written once, straight where DRAW reads them, and are never moved to join the list. Segments,
// their items and their palettes are kept from frame to frame: a list warm from a frame of a given
// size builds another such frame without allocating.

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <memory>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "throng/scenegraph/BodyLook.h"
#include "throng/scenegraph/Drawable.h"
#include "throng/scenegraph/FrameArena.h"
#include "throng/scenegraph/ItemTransform.h"
#include "throng/scenegraph/KeyPoseSource.h"
#include "throng/scenegraph/Math.h"

namespace throng {

class Node;

/// How an item shows its object; DRAW dispatches on it.
enum class Representation : std::uint8_t {
    Mesh,      ///< a mesh (rigid, or skinned when the item has a palette)
    Impostor,  ///< an image-based stand-in placed at the actor's Reference Point
    KeyPose,   ///< a skinned mesh whose vertices come from a key-pose cache (see `keyPose`)
};

/// Marks an item that belongs to no actor (generic scene geometry).
inline constexpr std::uint32_t kNoActor = ~std::uint32_t{0};

/// One thing to draw. Fields are ordered largest first to keep the item at three cache lines (192
/// bytes): a crowd writes one per drawn part every frame.
struct DrawItem {
    /// Every field at its default. Written out (not defaulted) so that a list appending a fresh item
    /// stores each field once, which the compiler can merge with the caller's own stores, instead of
    /// clearing the whole item first (value-initialisation, a slow `rep stos` per item).
    DrawItem() noexcept {}
    const Drawable* drawable = nullptr;  ///< the shared drawable data
    ItemTransform world;                 ///< where it stands (its model transform)
    const Node* node = nullptr;          ///< the node that produced it (a Geometry leaf, or an actor)
    const glm::mat4* skinPalette = nullptr;  ///< for skinned meshes: joint matrices (joint-to-model times
                                             ///< inverse bind), in the frame of `world`; else null
    double clipTime = 0.0;               ///< seconds into `clip` the actor shows this frame
    /// Weights of the mesh's morph targets (one per MeshData::morphTargets entry, kept by the list
    /// like palettes), or null: the mesh's neutral shape.
    const float* morphWeights = nullptr;
    std::uint32_t instance = 0;          ///< which of the node's instances (an actor of an actor group)
    std::uint32_t part = 0;              ///< index of the part within the instance (0 for a Geometry leaf)
    std::uint32_t skinPaletteSize = 0;   ///< number of matrices in `skinPalette`
    std::uint32_t actor = kNoActor;      ///< the actor (its id in its crowd), or kNoActor
    std::int32_t clip = -1;              ///< the clip the actor plays (its main clip for impostors), or -1
    glm::vec4 tint{1.0f};                ///< per-actor colour multiplier
    BodyLook look;                       ///< per-actor colours of the mesh's body regions
    Representation representation = Representation::Mesh;  ///< how it is shown
    std::uint16_t lodLevel = 0;          ///< level of detail chosen (0 = highest)
    KeyPoseRef keyPose;                  ///< Representation::KeyPose: the cached poses shown
};

/// A run of consecutive items of a DrawList, with the palettes they point to, filled by one
/// writer. Its memory is kept when it is cleared.
class DrawSegment {
public:
    /// Appends `item` as it is: its palette pointer must stay valid while the list is drawn (tests
    /// and hand-made lists). `primitives` is added to primitiveCount().
    void add(const DrawItem& item, std::uint64_t primitives) {
        items_.push_back(item);
        primitives_ += primitives;
    }
    /// Appends `item` placed by `world`, with a copy of `palette` kept by the segment (the item's
    /// pointer is set to the copy), so the list stays valid whatever happens to the scene.
    void add(const DrawItem& item, std::uint64_t primitives, const Mat4& world, std::span<const glm::mat4> palette = {}) {
        const std::span<glm::mat4> room = addSkinned(item, primitives, world, palette.size());
        std::copy(palette.begin(), palette.end(), room.begin());
    }
    /// Appends `item` placed by `world`, with room for a skin palette of `paletteSize` matrices kept
    /// by the segment; returns the room, for the caller to fill before the list is drawn.
    std::span<glm::mat4> addSkinned(const DrawItem& item, std::uint64_t primitives, const Mat4& world, std::size_t paletteSize) {
        DrawItem& added = copyIn(item, primitives, paletteSize);
        added.world = ItemTransform(world);
        return paletteRoom(added);
    }
    /// Appends an item with default fields but, when `paletteSize` is not 0, `skinPalette` (room for
    /// that many matrices, kept by the segment, to be filled before the list is drawn), and returns
    /// it for the caller to fill in place, its transform included. Hot loops make their items so:
    /// an item built elsewhere and copied in stalls on reading back its own stores.
    DrawItem& emplace(std::uint64_t primitives, std::size_t paletteSize = 0) {
        DrawItem& added = items_.emplace_back();
        // Items are written once and not read again this frame: the lines of the item eight items
        // ahead are fetched for writing now, so that its stores do not wait for them (the draw list
        // of 10k Table-2 actors -25 % side by side). A prefetch never faults, past the end included.
        // (Addresses as integers: a pointer past the storage's end would not be a valid pointer.)
        const std::uintptr_t ahead = reinterpret_cast<std::uintptr_t>(&added) + 8 * sizeof(DrawItem);
        for (std::size_t line = 0; line < sizeof(DrawItem); line += 64)
            __builtin_prefetch(reinterpret_cast<const void*>(ahead + line), 1);
        __builtin_prefetch(reinterpret_cast<const void*>(ahead + sizeof(DrawItem) - 1), 1);
        if (paletteSize) {
            added.skinPalette = palettes_.allocate(paletteSize);
            added.skinPaletteSize = static_cast<std::uint32_t>(paletteSize);
        }
        primitives_ += primitives;
        return added;
    }
    /// The palette of `item` (an item of this segment), for its writer to fill.
    static std::span<glm::mat4> paletteRoom(DrawItem& item) {
        return {const_cast<glm::mat4*>(item.skinPalette), item.skinPaletteSize};  // the segment's own memory
    }
    /// Gives `item` (an item of this segment) room for `count` morph weights kept by the segment,
    /// and returns it for the caller to fill before the list is drawn.
    std::span<float> addMorphWeights(DrawItem& item, std::size_t count) {
        float* room = weights_.allocate(count);
        item.morphWeights = room;
        return {room, count};
    }
    /// The items, in the order they were added.
    std::span<const DrawItem> items() const { return items_; }
    /// Number of items.
    std::size_t size() const { return items_.size(); }
    /// Total primitives of the items.
    std::uint64_t primitiveCount() const { return primitives_; }
    /// Reserves room for `n` items.
    void reserve(std::size_t n) { items_.reserve(n); }
    /// Empties the segment, keeping its memory.
    void clear() {
        items_.clear();
        palettes_.clear();
        weights_.clear();
        primitives_ = 0;
    }

private:
    friend class DrawList;
    // Appends a copy of `item` whose palette pointer is fresh room for `paletteSize` matrices.
    DrawItem& copyIn(const DrawItem& item, std::uint64_t primitives, std::size_t paletteSize) {
        DrawItem& added = emplace(primitives, paletteSize);
        const glm::mat4* palette = added.skinPalette;
        added = item;
        added.skinPalette = palette;
        added.skinPaletteSize = static_cast<std::uint32_t>(paletteSize);
        return added;
    }
    std::vector<DrawItem> items_;
    FrameArena<glm::mat4> palettes_;
    FrameArena<float> weights_;
    std::uint64_t primitives_ = 0;
};

/// An ordered list of draw items, made of segments, reused from frame to frame without reallocating.
class DrawList {
public:
    /// Every item of a list in order, across its segments (a forward range). Valid until the list
    /// is next changed.
    class Items {
    public:
        /// Walks the items segment by segment.
        class iterator {
        public:
            using iterator_category = std::forward_iterator_tag;  ///< standard iterator trait
            using value_type = DrawItem;                          ///< standard iterator trait
            using difference_type = std::ptrdiff_t;               ///< standard iterator trait
            using pointer = const DrawItem*;                      ///< standard iterator trait
            using reference = const DrawItem&;                    ///< standard iterator trait
            iterator() = default;
            /// The item.
            reference operator*() const { return (*segment_)->items()[index_]; }
            /// The item's members.
            pointer operator->() const { return &**this; }
            /// Moves to the next item, across segments.
            iterator& operator++() {
                ++index_;
                skipEnded();
                return *this;
            }
            /// Moves to the next item; returns where it was.
            iterator operator++(int) {
                iterator before = *this;
                ++*this;
                return before;
            }
            /// Whether both are at the same item (or both past the last).
            bool operator==(const iterator& other) const { return segment_ == other.segment_ && index_ == other.index_; }

        private:
            friend class Items;
            using Segments = const std::unique_ptr<DrawSegment>*;
            iterator(Segments segment, Segments end) : segment_(segment), end_(end) { skipEnded(); }
            void skipEnded() {
                while (segment_ != end_ && index_ == (*segment_)->size()) {
                    ++segment_;
                    index_ = 0;
                }
            }
            Segments segment_ = nullptr, end_ = nullptr;
            std::size_t index_ = 0;
        };
        /// The first item.
        iterator begin() const { return iterator(first_, last_); }
        /// Past the last item.
        iterator end() const { return iterator(last_, last_); }
        /// Number of items.
        std::size_t size() const { return size_; }
        /// Whether there is no item.
        bool empty() const { return size_ == 0; }
        /// Item `i` (walks the segments: for tests and occasional lookups, not for loops over the list).
        const DrawItem& operator[](std::size_t i) const {
            for (auto s = first_;; ++s) {
                if (i < (*s)->size()) return (*s)->items()[i];
                i -= (*s)->size();
            }
        }
        /// The first item (the list must not be empty).
        const DrawItem& front() const { return *begin(); }

    private:
        friend class DrawList;
        Items(const std::unique_ptr<DrawSegment>* first, const std::unique_ptr<DrawSegment>* last, std::size_t size)
            : first_(first), last_(last), size_(size) {}
        const std::unique_ptr<DrawSegment>* first_;
        const std::unique_ptr<DrawSegment>* last_;
        std::size_t size_;
    };

    /// Empties the list, keeping its segments and their memory.
    void clear() {
        for (std::size_t s = 0; s < used_; ++s) segments_[s]->clear();
        used_ = 0;
        serialOpen_ = false;
    }
    /// Reserves room for `n` items in the segment add() writes into next.
    void reserve(std::size_t n) { serial().reserve(n); }
    /// Appends `item` as it is (see DrawSegment::add).
    void add(const DrawItem& item, std::uint64_t primitives) { serial().add(item, primitives); }
    /// Appends `item` with copies of `world` and `palette` (see DrawSegment::add).
    void add(const DrawItem& item, std::uint64_t primitives, const Mat4& world, std::span<const glm::mat4> palette = {}) {
        serial().add(item, primitives, world, palette);
    }
    /// Appends `item` with a copy of `world` and room for its palette (see DrawSegment::addSkinned).
    std::span<glm::mat4> addSkinned(const DrawItem& item, std::uint64_t primitives, const Mat4& world, std::size_t paletteSize) {
        return serial().addSkinned(item, primitives, world, paletteSize);
    }
    /// Opens `count` empty segments at the end of the list, for writers that fill them apart (each
    /// chunk of a parallel loop its own); their items appear in segment order, whatever order they
    /// are filled in. Returns the index of the first; segment(i) gives each. Items added with add()
    /// afterwards go after them.
    std::size_t openSegments(std::size_t count) {
        const std::size_t first = used_;
        used_ += count;
        while (segments_.size() < used_) segments_.push_back(std::make_unique<DrawSegment>());
        serialOpen_ = false;
        return first;
    }
    /// Segment `i` (opened this frame).
    DrawSegment& segment(std::size_t i) { return *segments_[i]; }
    /// Appends every item of `other` in order, with copies of their palettes and morph weights.
    void append(const DrawList& other) {
        DrawSegment& into = serial();
        for (const DrawItem& item : other.items()) {
            DrawItem* added = nullptr;
            if (!item.skinPalette) {
                into.add(item, 0);
                added = &into.items_.back();
            } else {
                added = &into.copyIn(item, 0, item.skinPaletteSize);
                std::copy_n(item.skinPalette, item.skinPaletteSize, DrawSegment::paletteRoom(*added).begin());
            }
            if (item.morphWeights) {
                const std::size_t n = item.drawable->morphTargetCount();
                std::copy_n(item.morphWeights, n, into.addMorphWeights(*added, n).begin());
            }
        }
        into.primitives_ += other.primitiveCount();  // as the other list counted them
    }
    /// The items, in the order CULL produced them.
    Items items() const { return Items(segments_.data(), segments_.data() + used_, size()); }
    /// Number of items.
    std::size_t size() const {
        std::size_t n = 0;
        for (std::size_t s = 0; s < used_; ++s) n += segments_[s]->size();
        return n;
    }
    /// Total primitives of all items.
    std::uint64_t primitiveCount() const {
        std::uint64_t n = 0;
        for (std::size_t s = 0; s < used_; ++s) n += segments_[s]->primitiveCount();
        return n;
    }

private:
    // The segment add() writes into: the last one, unless segments were opened for other writers
    // since, in which case a new one after them.
    DrawSegment& serial() {
        if (!serialOpen_) {
            openSegments(1);
            serialOpen_ = true;
        }
        return *segments_[used_ - 1];
    }
    std::vector<std::unique_ptr<DrawSegment>> segments_;  // kept across frames; the first used_ are in use
    std::size_t used_ = 0;
    bool serialOpen_ = false;
};

}  // namespace throng
