#pragma once
// The output of CULL and the input of DRAW: what to draw, with which matrix, in traversal order.

#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include "throng/scenegraph/Math.h"

namespace throng {

class Drawable;
class Node;

/// One thing to draw.
struct DrawItem {
    const Drawable* drawable = nullptr;  ///< the shared drawable data
    const Mat4* worldMatrix = nullptr;   ///< its model matrix; valid until the next matrices-and-bounds pass
    const Node* node = nullptr;          ///< the node that produced it (a Geometry leaf, or an actor)
    std::uint32_t instance = 0;          ///< which of the node's instances (an actor of an actor group)
    std::uint32_t part = 0;              ///< index of the part within the instance (0 for a Geometry leaf)
    std::uint32_t lodLevel = 0;          ///< level of detail chosen (0 = highest)
    const glm::mat4* skinPalette = nullptr;  ///< for skinned meshes: joint matrices (joint-to-model times
                                             ///< inverse bind), in the frame of `worldMatrix`; else null
    std::uint32_t skinPaletteSize = 0;   ///< number of matrices in `skinPalette`
    glm::vec4 tint{1.0f};                ///< per-actor colour multiplier
};

/// An ordered list of draw items with running totals, reused from frame to frame without reallocating.
class DrawList {
public:
    /// Empties the list, keeping its capacity.
    void clear() { items_.clear(); primitives_ = 0; }
    /// Reserves room for `n` items.
    void reserve(std::size_t n) { items_.reserve(n); }
    /// Appends an item; `primitives` is added to primitiveCount().
    void add(const DrawItem& item, std::uint64_t primitives) {
        items_.push_back(item);
        primitives_ += primitives;
    }
    /// The items, in the order CULL produced them.
    const std::vector<DrawItem>& items() const { return items_; }
    /// Number of items.
    std::size_t size() const { return items_.size(); }
    /// Total primitives of all items.
    std::uint64_t primitiveCount() const { return primitives_; }

private:
    std::vector<DrawItem> items_;
    std::uint64_t primitives_ = 0;
};

}  // namespace throng
