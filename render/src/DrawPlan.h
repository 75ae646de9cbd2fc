#pragma once
// Internal to render: the CPU half of GlRenderer::draw, kept apart from the GL so that a test can
// check it without a context. The drawing order (list order, or nearest first by distance band),
// the batches items gather into (one instanced draw each: same mesh or key-pose cache, same path
// and winding, same band), and an item's instance record (its model matrix made eye-relative in
// double before rounding to float, so a crowd far from the world origin keeps its precision).

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "throng/scenegraph/DrawList.h"

namespace throng::detail {

/// No batch (yet) for this variant in this draw.
inline constexpr std::uint32_t kNoBatch = 0xffffffffu;

/// The distance band of front-to-back drawing: [0, 16 m), then each band twice as deep as the last
/// (infinite and NaN distances fall in the last band and band 0).
std::int32_t distanceBand(float distance);

/// The drawing order of `items`, and each item's distance band.
class DrawOrder {
public:
    /// Fills order() with the items' indices: in list order, or with `frontToBack` nearest first by
    /// the nearest point of each item's bounding sphere seen from `eye` (ties keep list order; an
    /// item without drawable counts as at the eye), and band() with their bands (0 otherwise).
    void plan(std::span<const DrawItem* const> items, const Vec3& eye, bool frontToBack);
    /// Item indices in drawing order.
    const std::vector<std::uint32_t>& order() const { return order_; }
    /// Each item's distance band, by item index.
    const std::vector<std::int32_t>& band() const { return band_; }

private:
    std::vector<std::uint32_t> order_;
    std::vector<std::int32_t> band_;
    std::vector<std::pair<float, std::uint32_t>> byDistance_;
};

/// Where the open batches of one mesh (or key-pose cache) are in the current draw: one per variant
/// (skinned or not, or blended or not, times mirrored or not). Kept on the mesh's own record so
/// that finding an item's batch costs no lookup.
struct BatchSlots {
    std::uint64_t stamp = 0;                                        ///< the draw that set `batch`
    std::uint32_t batch[4] = {kNoBatch, kNoBatch, kNoBatch, kNoBatch};  ///< per variant
};

/// One batch: its items' count and, once laid out, its slots in the instance buffer.
struct Batch {
    std::uint32_t count = 0;   ///< items
    std::uint32_t first = 0;   ///< first slot in the instance buffer (after layOut)
    std::uint32_t filled = 0;  ///< slots written so far
    std::int32_t band = 0;     ///< the distance band of its items
};

/// Gathers the items of one draw into batches, in order of first appearance.
class BatchPlanner {
public:
    /// Starts a draw; with `instancing` off every item is a batch of its own.
    void begin(bool instancing);
    /// The batch of an item drawn through `slots` as `variant` (0-3) in `band`: the variant's open
    /// batch when instancing is on and its band is the same, else a new one (then `opened` is set).
    std::uint32_t join(BatchSlots& slots, int variant, std::int32_t band, bool& opened);
    /// A new batch of one item (an item that cannot share its draw).
    std::uint32_t alone(std::int32_t band);
    /// Gives each batch its run of slots, in batch order; returns the slots in all.
    std::uint32_t layOut();
    /// The next free slot of batch `b` (after layOut), in the order its items come.
    std::uint32_t nextSlot(std::uint32_t b) { return batches_[b].first + batches_[b].filled++; }
    /// The batches of this draw.
    const std::vector<Batch>& batches() const { return batches_; }

private:
    std::vector<Batch> batches_;
    std::uint64_t stamp_ = 0;
    bool instancing_ = true;
};

/// Per-instance vertex data: the eye-relative model matrix, the tint, the palette's first matrix
/// (key-pose items: the first texel of row 0, the first texel of row 1 and row 1's weight) and the
/// body look.
struct InstanceData {
    float model[16];           ///< column-major, translation relative to the eye
    float tint[4];             ///< the item's tint
    std::int32_t paletteBase;  ///< first palette matrix (or row 0's first texel)
    std::int32_t row1Base;     ///< key-pose blends: row 1's first texel
    float blend;               ///< key-pose blends: row 1's weight (read as the bits of an int)
    std::int32_t pad;          ///< aligns the look
    std::uint32_t look[4];     ///< the item's BodyLook
};
static_assert(sizeof(InstanceData) == 112, "instance attributes assume a 112-byte stride");

/// The instance record of `item` seen from `eye`: T(-eye) * world, the translation subtracted in
/// double and then rounded; tint copied; palette fields zero (the caller sets them per path).
void writeInstance(InstanceData& d, const DrawItem& item, const Vec3& eye);

}  // namespace throng::detail
