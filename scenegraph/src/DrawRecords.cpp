#include "throng/scenegraph/DrawRecords.h"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "throng/scenegraph/ByteStream.h"
#include "throng/scenegraph/KeyPoseSource.h"

namespace throng {
namespace {

constexpr char kMagic[4] = {'T', 'D', 'R', 'W'};

// One item's fixed part; its palette (16 floats per matrix) and morph weights follow it. Laid out
// without padding, so that every byte written is a value.
struct RecordHead {
    double clipTime;
    double translation[3];
    float linear[9];
    float tint[4];
    float blend;
    std::uint32_t look[4];
    std::uint32_t drawable, node, source, instance, part, actor;
    std::int32_t clip;
    std::uint32_t paletteSize, weightCount;
    std::uint32_t skin, pose[2], row[2];
    std::uint16_t lodLevel;
    std::uint8_t representation, reserved8;
    std::uint32_t reserved32;
};
static_assert(sizeof(RecordHead) == 168, "a record head has no padding");  // 8-byte aligned, fields summing to 168

// Whether every value of `values` is finite.
bool allFinite(const float* values, std::size_t n) {
    bool finite = true;
    for (std::size_t i = 0; i < n; ++i) finite &= std::isfinite(values[i]);
    return finite;
}

// Whether every float in `bytes` (any alignment) is finite.
bool allFinite(std::span<const std::byte> bytes) {
    bool finite = true;
    for (std::size_t at = 0; at + sizeof(float) <= bytes.size(); at += sizeof(float)) {
        float v;
        std::memcpy(&v, bytes.data() + at, sizeof v);
        finite &= std::isfinite(v);
    }
    return finite;
}

// Throws for record `r` of `count` of the message `in` reads.
[[noreturn]] void refuse(const ByteReader& in, std::uint64_t r, std::uint64_t count, const std::string& why) {
    throw std::invalid_argument(in.source() + ", record " + std::to_string(r) + " of " + std::to_string(count) + ": " + why);
}

// Appends the item of the (checked) record at `at` of `bytes` to `segment`.
void append(std::span<const std::byte> bytes, std::size_t at, const DrawReferences& refs, DrawSegment& segment) {
    RecordHead h;
    std::memcpy(&h, bytes.data() + at, sizeof h);
    const Drawable* drawable = refs.drawable(h.drawable);
    DrawItem& item = segment.emplace(drawable->primitiveCount(), h.paletteSize);
    item.drawable = drawable;
    item.world.translation = Vec3(h.translation[0], h.translation[1], h.translation[2]);
    std::memcpy(&item.world.linear[0][0], h.linear, sizeof h.linear);
    item.node = refs.node(h.node);
    item.clipTime = h.clipTime;
    item.instance = h.instance;
    item.part = h.part;
    item.actor = h.actor;
    item.clip = h.clip;
    item.tint = glm::vec4(h.tint[0], h.tint[1], h.tint[2], h.tint[3]);
    std::memcpy(item.look.rgba.data(), h.look, sizeof h.look);
    item.representation = Representation(h.representation);
    item.lodLevel = h.lodLevel;
    if (item.representation == Representation::KeyPose) {
        item.keyPose.source = refs.keyPoseSource(h.source);
        item.keyPose.skin = h.skin;
        for (int k = 0; k < 2; ++k) item.keyPose.pose[k] = h.pose[k], item.keyPose.row[k] = h.row[k];
        item.keyPose.blend = h.blend;
    }
    const std::byte* tail = bytes.data() + at + sizeof h;
    if (h.paletteSize) std::memcpy(DrawSegment::paletteRoom(item).data(), tail, std::size_t{h.paletteSize} * sizeof(glm::mat4));
    if (h.weightCount)
        std::memcpy(segment.addMorphWeights(item, h.weightCount).data(), tail + std::size_t{h.paletteSize} * sizeof(glm::mat4),
                    h.weightCount * sizeof(float));
}

}  // namespace

// Checks message `m` whole and lists its records (throws naming what is wrong).
void DrawRecordMerger::index(std::span<const std::byte> bytes, std::size_t m, const DrawReferences& refs, std::vector<Entry>& entries) {
    entries.clear();
    ByteReader in(bytes, "mergeDrawRecords: message " + std::to_string(m));
    char magic[4];
    in.read(magic, 4, "the header");
    if (std::memcmp(magic, kMagic, 4) != 0) throw std::invalid_argument(in.source() + ": not draw records");
    const auto count = in.get<std::uint64_t>("the header");
    if (count > in.remaining() / sizeof(RecordHead))
        throw std::invalid_argument(in.source() + ": " + std::to_string(count) + " records announced in " + std::to_string(in.remaining()) +
                                    " bytes");
    entries.reserve(count);
    std::uint64_t lastKey = 0;
    for (std::uint64_t r = 0; r < count; ++r) {
        const std::size_t at = in.offset();
        const auto h = in.get<RecordHead>("a record");  // there is room: see the count's check
        const Drawable* drawable = refs.drawable(h.drawable);
        if (!drawable)
            refuse(in, r, count, "drawable " + std::to_string(h.drawable) + " is not numbered here (" + std::to_string(refs.drawableCount()) + " are)");
        if (!refs.node(h.node))
            refuse(in, r, count, "node " + std::to_string(h.node) + " is not numbered here (" + std::to_string(refs.nodeCount()) + " are)");
        if (h.actor == kNoActor) refuse(in, r, count, "no actor");
        if (h.representation > std::uint8_t(Representation::KeyPose))
            refuse(in, r, count, "representation " + std::to_string(h.representation) + " is none");
        if (h.representation == std::uint8_t(Representation::KeyPose)) {
            const KeyPoseSource* source = refs.keyPoseSource(h.source);
            if (!source) refuse(in, r, count, "key-pose source " + std::to_string(h.source) + " is not numbered here");
            for (int k = 0; k < 2; ++k)
                if (h.pose[k] >= source->poseCount() || h.row[k] >= source->rowCount())
                    refuse(in, r, count,
                           "key-pose " + std::to_string(h.pose[k]) + " in row " + std::to_string(h.row[k]) + " of a source of " +
                               std::to_string(source->poseCount()) + " poses and " + std::to_string(source->rowCount()) + " rows");
        } else if (h.source != DrawReferences::kNone) {
            refuse(in, r, count, "a key-pose source on an item that is not a key-pose");
        }
        if (h.paletteSize > kMaxRecordPaletteSize)
            refuse(in, r, count, std::to_string(h.paletteSize) + " palette matrices (at most " + std::to_string(kMaxRecordPaletteSize) + ")");
        if (h.weightCount != 0 && h.weightCount != drawable->morphTargetCount())
            refuse(in, r, count,
                   std::to_string(h.weightCount) + " morph weights for a drawable of " + std::to_string(drawable->morphTargetCount()) +
                       " morph targets");
        if (!std::isfinite(h.clipTime) || !std::isfinite(h.translation[0]) || !std::isfinite(h.translation[1]) ||
            !std::isfinite(h.translation[2]) || !allFinite(h.linear, 9) || !allFinite(h.tint, 4) || !std::isfinite(h.blend))
            refuse(in, r, count, "a number that is not finite (clip time, placement, tint or blend)");
        const std::size_t tail = (std::size_t{16} * h.paletteSize + h.weightCount) * sizeof(float);
        if (in.remaining() < tail)
            refuse(in, r, count, "the bytes end at " + std::to_string(bytes.size()) + " inside its palette and morph weights");
        if (!allFinite(in.take(tail, "a record's palette and morph weights")))
            refuse(in, r, count, "a palette matrix or morph weight that is not finite");
        const std::uint64_t key = std::uint64_t{h.node} << 32 | h.instance;
        if (r > 0 && key < lastKey)
            refuse(in, r, count, "out of order (node " + std::to_string(h.node) + ", instance " + std::to_string(h.instance) + ")");
        lastKey = key;
        entries.push_back({key, at});
    }
    if (in.remaining() != 0) throw std::invalid_argument(in.source() + ": " + std::to_string(in.remaining()) + " bytes after the last record");
}

std::size_t writeDrawRecords(const DrawList& list, const DrawReferences& refs, std::vector<std::byte>& out) {
    const std::size_t start = out.size();
    ByteWriter w(out);
    w.putBytes(kMagic, 4);
    w.put(std::uint64_t{0});  // the count, written when known
    std::uint64_t count = 0, index = 0;
    try {
        for (const DrawItem& item : list.items()) {
            const std::uint64_t n = index++;
            if (item.actor == kNoActor) continue;
            auto refuse = [&](const char* what) {
                throw std::invalid_argument("writeDrawRecords: item " + std::to_string(n) + " (actor " + std::to_string(item.actor) + ")'s " +
                                            what + " has no number here");
            };
            RecordHead h{};
            h.drawable = refs.numberOf(item.drawable);
            h.node = refs.numberOf(item.node);
            if (h.drawable == DrawReferences::kNone) refuse("drawable");
            if (h.node == DrawReferences::kNone) refuse("node");
            h.source = DrawReferences::kNone;
            if (item.representation == Representation::KeyPose) {
                h.source = refs.numberOf(item.keyPose.source);
                if (h.source == DrawReferences::kNone) refuse("key-pose source");
                h.skin = item.keyPose.skin;
                for (int k = 0; k < 2; ++k) h.pose[k] = item.keyPose.pose[k], h.row[k] = item.keyPose.row[k];
                h.blend = item.keyPose.blend;
            }
            h.clipTime = item.clipTime;
            for (int k = 0; k < 3; ++k) h.translation[k] = item.world.translation[k];
            std::memcpy(h.linear, &item.world.linear[0][0], sizeof h.linear);
            for (int k = 0; k < 4; ++k) h.tint[k] = item.tint[k];
            std::memcpy(h.look, item.look.rgba.data(), sizeof h.look);
            h.instance = item.instance;
            h.part = item.part;
            h.actor = item.actor;
            h.clip = item.clip;
            h.paletteSize = item.skinPalette ? item.skinPaletteSize : 0;
            h.weightCount = item.morphWeights ? item.drawable->morphTargetCount() : 0;
            h.lodLevel = item.lodLevel;
            h.representation = std::uint8_t(item.representation);
            w.put(h);
            if (h.paletteSize) w.putBytes(item.skinPalette, std::size_t{h.paletteSize} * sizeof(glm::mat4));
            if (h.weightCount) w.putBytes(item.morphWeights, h.weightCount * sizeof(float));
            ++count;
        }
    } catch (...) {
        out.resize(start);
        throw;
    }
    std::memcpy(out.data() + start + 4, &count, sizeof count);
    return count;
}

void DrawRecordMerger::merge(std::span<const std::span<const std::byte>> messages, const DrawReferences& refs, DrawList& into) {
    // Every message checked and indexed before anything is appended.
    if (entries_.size() < messages.size()) entries_.resize(messages.size());
    std::size_t total = 0;
    for (std::size_t m = 0; m < messages.size(); ++m) {
        index(messages[m], m, refs, entries_[m]);
        total += entries_[m].size();
    }
    DrawSegment& segment = into.segment(into.openSegments(1));
    segment.reserve(segment.size() + total);
    // Each message is in order: take the least key among the messages' next records each time
    // (few messages: one per process).
    next_.assign(messages.size(), 0);
    for (std::size_t done = 0; done < total; ++done) {
        std::size_t best = messages.size();
        for (std::size_t m = 0; m < messages.size(); ++m)
            if (next_[m] < entries_[m].size() && (best == messages.size() || entries_[m][next_[m]].key < entries_[best][next_[best]].key))
                best = m;
        append(messages[best], entries_[best][next_[best]++].at, refs, segment);
    }
}

}  // namespace throng
