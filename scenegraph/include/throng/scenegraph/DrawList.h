#pragma once
// The output of CULL and the input of DRAW: what to draw, with which matrix, in traversal order.
// A list owns copies of the matrices and skin palettes its items use, so it describes its frame
// completely: DRAW may render it while the next frame is stepped and culled (Performer's
// multiprocess mode), and nothing at draw time needs to look back into the scene or the crowd.

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "throng/scenegraph/FrameArena.h"
#include "throng/scenegraph/KeyPoseSource.h"
#include "throng/scenegraph/Math.h"

namespace throng {

class Drawable;
class Node;

/// How an item shows its object; DRAW dispatches on it.
enum class Representation : std::uint8_t {
    Mesh,      ///< a mesh (rigid, or skinned when the item has a palette)
    Impostor,  ///< an image-based stand-in placed at the actor's Reference Point
    KeyPose,   ///< a skinned mesh whose vertices come from a key-pose cache (see `keyPose`)
};

/// Marks an item that belongs to no actor (generic scene geometry).
inline constexpr std::uint32_t kNoActor = ~std::uint32_t{0};

/// One thing to draw.
struct DrawItem {
    const Drawable* drawable = nullptr;  ///< the shared drawable data
    const Mat4* worldMatrix = nullptr;   ///< its model matrix (owned by the list when added with one)
    const Node* node = nullptr;          ///< the node that produced it (a Geometry leaf, or an actor)
    std::uint32_t instance = 0;          ///< which of the node's instances (an actor of an actor group)
    std::uint32_t part = 0;              ///< index of the part within the instance (0 for a Geometry leaf)
    std::uint32_t lodLevel = 0;          ///< level of detail chosen (0 = highest)
    const glm::mat4* skinPalette = nullptr;  ///< for skinned meshes: joint matrices (joint-to-model times
                                             ///< inverse bind), in the frame of `worldMatrix`; else null
    std::uint32_t skinPaletteSize = 0;   ///< number of matrices in `skinPalette`
    glm::vec4 tint{1.0f};                ///< per-actor colour multiplier
    std::uint32_t actor = kNoActor;      ///< the actor (its id in its crowd), or kNoActor
    Representation representation = Representation::Mesh;  ///< how it is shown
    std::int32_t clip = -1;              ///< the clip the actor plays (its main clip for impostors), or -1
    double clipTime = 0.0;               ///< seconds into `clip` the actor shows this frame
    KeyPoseRef keyPose;                  ///< Representation::KeyPose: the cached poses shown
};

/// An ordered list of draw items with running totals, reused from frame to frame without reallocating.
class DrawList {
public:
    /// Empties the list and its matrix storage, keeping their capacity.
    void clear() {
        items_.clear();
        primitives_ = 0;
        own_.clear();
        for (Storage& s : adopted_) {
            s.clear();
            spares_.push_back(std::move(s));
        }
        adopted_.clear();
    }
    /// Reserves room for `n` items.
    void reserve(std::size_t n) { items_.reserve(n); }
    /// Appends `item` as it is: its matrix and palette pointers must stay valid while the list is
    /// drawn (tests and hand-made lists). `primitives` is added to primitiveCount().
    void add(const DrawItem& item, std::uint64_t primitives) {
        items_.push_back(item);
        primitives_ += primitives;
    }
    /// Appends `item` with copies of `world` and `palette` kept by the list (the item's pointers
    /// are set to the copies), so the list stays valid whatever happens to the scene.
    void add(const DrawItem& item, std::uint64_t primitives, const Mat4& world, std::span<const glm::mat4> palette = {}) {
        const std::span<glm::mat4> room = addSkinned(item, primitives, world, palette.size());
        std::copy(palette.begin(), palette.end(), room.begin());
    }
    /// Appends `item` with a copy of `world` and room for a skin palette of `paletteSize` matrices,
    /// both kept by the list; returns the room, for the caller to fill before the list is drawn.
    std::span<glm::mat4> addSkinned(const DrawItem& item, std::uint64_t primitives, const Mat4& world, std::size_t paletteSize) {
        glm::mat4* palette = paletteSize ? own_.palettes.allocate(paletteSize) : nullptr;
        const Mat4* matrix = own_.matrices.push(world);
        // The item is copied once, into the list, and its pointers set there: crowds add thousands
        // of items a frame, and each extra copy of a just-built item stalls on its stores.
        DrawItem& added = items_.emplace_back(item);
        added.worldMatrix = matrix;
        added.skinPalette = palette;
        added.skinPaletteSize = static_cast<std::uint32_t>(paletteSize);
        primitives_ += primitives;
        return {palette, paletteSize};
    }
    /// Appends every item of `other` in order, with copies of their matrices and palettes.
    void append(const DrawList& other) {
        for (const DrawItem& item : other.items_) {
            if (!item.worldMatrix) {
                items_.push_back(item);
                continue;
            }
            add(item, 0, *item.worldMatrix,
                item.skinPalette ? std::span<const glm::mat4>(item.skinPalette, item.skinPaletteSize)
                                 : std::span<const glm::mat4>());
        }
        primitives_ += other.primitives_;
    }
    /// Moves every item of `other` to the end of this list, in order, together with the storage
    /// their matrices and palettes live in (nothing is copied but the items). `other` is left empty
    /// with storage this list no longer needs, so lists that splice into each other frame after
    /// frame stop allocating once warm. Items `other` holds with outside pointers keep them.
    void splice(DrawList& other) {
        items_.insert(items_.end(), other.items_.begin(), other.items_.end());
        primitives_ += other.primitives_;
        other.items_.clear();
        other.primitives_ = 0;
        for (Storage& s : other.adopted_) adopted_.push_back(std::move(s));
        other.adopted_.clear();
        adopted_.push_back(std::move(other.own_));
        if (spares_.empty()) {
            other.own_ = Storage{};
        } else {
            other.own_ = std::move(spares_.back());
            spares_.pop_back();
        }
    }
    /// The items, in the order CULL produced them.
    const std::vector<DrawItem>& items() const { return items_; }
    /// Number of items.
    std::size_t size() const { return items_.size(); }
    /// Total primitives of all items.
    std::uint64_t primitiveCount() const { return primitives_; }

private:
    // Where the list's own copies of matrices and palettes live.
    struct Storage {
        FrameArena<Mat4> matrices;
        FrameArena<glm::mat4> palettes;
        void clear() {
            matrices.clear();
            palettes.clear();
        }
    };
    std::vector<DrawItem> items_;
    std::uint64_t primitives_ = 0;
    Storage own_;                    // what add() writes into
    std::vector<Storage> adopted_;   // storage spliced in with other lists' items
    std::vector<Storage> spares_;    // cleared storage, handed to lists that splice into this one
};

}  // namespace throng
