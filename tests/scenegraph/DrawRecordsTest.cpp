// Draw records: items of actors written as bytes and merged back into a list, field for field and
// in one process's order; every damaged message refused with its place named, the list untouched.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <vector>

#include "throng/scenegraph/DrawRecords.h"
#include "throng/scenegraph/Group.h"

using namespace throng;

namespace {

// A source of 4 rows over 10 poses (no palettes needed here).
class FourRows : public KeyPoseSource {
public:
    std::uint32_t rowCount() const override { return 4; }
    std::uint32_t poseCount() const override { return 10; }
    std::span<const glm::mat4> palette(std::uint32_t, std::uint32_t) const override { return {}; }
};

// Two nodes, three drawables (one with two morph targets), one key-pose source, all numbered.
struct Scene {
    Group first, second;
    Drawable body{"body", BoundingSphere(Vec3(0.0), 1.0), 100};
    Drawable face{"face", BoundingSphere(Vec3(0.0), 0.2), 40, 2};
    Drawable impostor{"impostor", BoundingSphere(Vec3(0.0), 1.0), 2};
    Drawable street{"street", BoundingSphere(Vec3(0.0), 50.0), 8};  // scene geometry, not numbered
    FourRows rows;
    DrawReferences refs;
    Scene() {
        refs.addNode(first), refs.addNode(second);
        refs.addDrawable(body), refs.addDrawable(face), refs.addDrawable(impostor);
        refs.addKeyPoseSource(rows);
    }
};

// Appends an item of `actor` (instance `instance` of `node`) showing `drawable`.
DrawItem& addItem(DrawSegment& segment, const Node& node, std::uint32_t instance, const Drawable& drawable, std::uint32_t actor,
                  std::size_t palette = 0) {
    DrawItem& item = segment.emplace(drawable.primitiveCount(), palette);
    item.drawable = &drawable;
    item.node = &node;
    item.instance = instance;
    item.actor = actor;
    item.part = instance % 3;
    item.clip = int(actor % 2);
    item.clipTime = 0.25 * actor;
    item.tint = glm::vec4(0.5f, 0.25f, 1.0f, 1.0f);
    item.look.rgba = {packBodyColour(1, 2, 3), 0, packBodyColour(4, 5, 6), 0};
    item.lodLevel = std::uint16_t(actor % 3);
    Mat4 world(1.0);
    world[3] = Vec4(1000.5 + actor, 0.0, -2.25 * actor, 1.0);
    world[0] = Vec4(0.0, 0.0, -1.0, 0.0), world[2] = Vec4(1.0, 0.0, 0.0, 0.0);
    item.world = ItemTransform(world);
    for (std::size_t j = 0; j < palette; ++j) DrawSegment::paletteRoom(item)[j] = glm::mat4(float(actor + j));
    return item;
}

// A list as one process would make it for actors 0-5: a street (no actor), then instances 0-3 of
// the first node (skinned, with a face, an impostor, a key-pose) and instances 0-1 of the second.
void fill(Scene& s, DrawList& list, std::span<const std::uint32_t> actors) {
    DrawSegment& segment = list.segment(list.openSegments(1));
    DrawItem& street = segment.emplace(s.street.primitiveCount());
    street.drawable = &s.street;
    for (std::uint32_t a : actors) {
        const Node& node = a < 4 ? static_cast<const Node&>(s.first) : s.second;
        const std::uint32_t instance = a < 4 ? a : a - 4;
        if (a == 2) {
            addItem(segment, node, instance, s.impostor, a).representation = Representation::Impostor;
            continue;
        }
        if (a == 3) {
            DrawItem& item = addItem(segment, node, instance, s.body, a);
            item.representation = Representation::KeyPose;
            item.keyPose = KeyPoseRef{&s.rows, 0, {7, 8}, {1, 3}, 0.375f};
            continue;
        }
        addItem(segment, node, instance, s.body, a, 3 + a);
        DrawItem& face = addItem(segment, node, instance, s.face, a);
        const std::span<float> w = segment.addMorphWeights(face, 2);
        w[0] = 0.5f, w[1] = float(a);
    }
}

// Item by item, every field and what its pointers point to.
void expectSameItems(const DrawList& expected, const DrawList& got) {
    ASSERT_EQ(got.size(), expected.size());
    auto g = got.items().begin();
    for (const DrawItem& e : expected.items()) {
        const DrawItem& i = *g++;
        EXPECT_EQ(i.drawable, e.drawable);
        EXPECT_EQ(i.node, e.node);
        EXPECT_TRUE(i.world == e.world);
        EXPECT_EQ(i.actor, e.actor);
        EXPECT_EQ(i.instance, e.instance);
        EXPECT_EQ(i.part, e.part);
        EXPECT_EQ(i.clip, e.clip);
        EXPECT_EQ(i.clipTime, e.clipTime);
        EXPECT_EQ(i.tint, e.tint);
        EXPECT_TRUE(i.look == e.look);
        EXPECT_EQ(i.representation, e.representation);
        EXPECT_EQ(i.lodLevel, e.lodLevel);
        ASSERT_EQ(i.skinPaletteSize, e.skinPaletteSize);
        ASSERT_EQ(i.skinPalette != nullptr, e.skinPalette != nullptr);
        for (std::uint32_t j = 0; j < e.skinPaletteSize; ++j) EXPECT_EQ(i.skinPalette[j], e.skinPalette[j]);
        ASSERT_EQ(i.morphWeights != nullptr, e.morphWeights != nullptr);
        for (std::uint32_t j = 0; e.morphWeights && j < e.drawable->morphTargetCount(); ++j) EXPECT_EQ(i.morphWeights[j], e.morphWeights[j]);
        EXPECT_EQ(i.keyPose.source, e.keyPose.source);
        EXPECT_EQ(i.keyPose.pose[0], e.keyPose.pose[0]);
        EXPECT_EQ(i.keyPose.pose[1], e.keyPose.pose[1]);
        EXPECT_EQ(i.keyPose.row[0], e.keyPose.row[0]);
        EXPECT_EQ(i.keyPose.row[1], e.keyPose.row[1]);
        EXPECT_EQ(i.keyPose.blend, e.keyPose.blend);
    }
}

// The message of `list`.
std::vector<std::byte> message(const DrawList& list, const DrawReferences& refs) {
    std::vector<std::byte> bytes;
    writeDrawRecords(list, refs, bytes);
    return bytes;
}

// The error merging `bytes` alone into `into` gives ("" if none).
std::string refusal(const std::vector<std::byte>& bytes, const DrawReferences& refs, DrawList& into) {
    const std::span<const std::byte> one[1] = {bytes};
    try {
        DrawRecordMerger().merge(one, refs, into);
    } catch (const std::invalid_argument& e) {
        return e.what();
    }
    return "";
}

}  // namespace

// Every actor item comes back as it was, its palette and weights copied; the street stays behind.
TEST(DrawRecords, ItemsComeBackFieldForField) {
    Scene s;
    DrawList whole, actorsOnly, merged;
    const std::uint32_t all[] = {0, 1, 2, 3, 4, 5};
    fill(s, whole, all);
    const std::vector<std::byte> bytes = message(whole, s.refs);
    for (const DrawItem& item : whole.items())
        if (item.actor != kNoActor) actorsOnly.add(item, item.drawable->primitiveCount());
    const std::span<const std::byte> one[1] = {bytes};
    DrawRecordMerger().merge(one, s.refs, merged);
    expectSameItems(actorsOnly, merged);
    EXPECT_EQ(merged.primitiveCount(), whole.primitiveCount() - s.street.primitiveCount());
}

// Actors split over three processes, each writing its own: merged, they come in one process's order.
TEST(DrawRecords, MessagesOfSeveralProcessesMergeInOneProcesssOrder) {
    Scene s;
    DrawList whole;
    const std::uint32_t all[] = {0, 1, 2, 3, 4, 5}, p0[] = {1, 4}, p1[] = {0, 3, 5}, p2[] = {2};
    fill(s, whole, all);
    std::vector<std::vector<std::byte>> bytes;
    for (std::span<const std::uint32_t> part : {std::span<const std::uint32_t>(p0), std::span<const std::uint32_t>(p1),
                                                 std::span<const std::uint32_t>(p2)}) {
        DrawList list;
        fill(s, list, part);
        bytes.push_back(message(list, s.refs));
    }
    const std::span<const std::byte> messages[3] = {bytes[0], bytes[1], bytes[2]};
    DrawList merged, actorsOnly;
    DrawItem street;
    street.drawable = &s.street;
    merged.add(street, 8);  // what the drawing process already holds stays first
    actorsOnly.add(street, 8);
    for (const DrawItem& item : whole.items())
        if (item.actor != kNoActor) actorsOnly.add(item, 0);
    DrawRecordMerger merger;
    merger.merge(messages, s.refs, merged);
    expectSameItems(actorsOnly, merged);
    EXPECT_EQ(merged.primitiveCount(), whole.primitiveCount());
    // The merger's scratch serves the next frame: the same again, appended.
    merger.merge(messages, s.refs, merged);
    EXPECT_EQ(merged.size(), 1 + 2 * (actorsOnly.size() - 1));
}

// An item whose drawable or node this process does not number cannot be written; nothing is.
TEST(DrawRecords, WritingAnUnnumberedThingThrowsAndWritesNothing) {
    Scene s;
    DrawList list;
    const std::uint32_t some[] = {0};
    fill(s, list, some);
    Drawable stray("stray", BoundingSphere(Vec3(0.0), 1.0), 1);
    DrawItem item;
    item.drawable = &stray, item.node = &s.first, item.actor = 9;
    list.add(item, 1);
    std::vector<std::byte> out(3, std::byte{7});
    try {
        writeDrawRecords(list, s.refs, out);
        FAIL() << "an unnumbered drawable was written";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("item 3 (actor 9)'s drawable has no number"), std::string::npos) << e.what();
    }
    EXPECT_EQ(out, std::vector<std::byte>(3, std::byte{7}));
}

// Cut short anywhere, a message is refused with where it ends, and the list is left as it was.
TEST(DrawRecords, AMessageCutShortAnywhereIsRefused) {
    Scene s;
    DrawList whole;
    const std::uint32_t all[] = {0, 1, 2, 3, 4, 5};
    fill(s, whole, all);
    const std::vector<std::byte> bytes = message(whole, s.refs);
    DrawList into;
    DrawItem street;
    street.drawable = &s.street;
    into.add(street, 8);
    for (std::size_t n = 0; n < bytes.size(); ++n) {
        const std::string why = refusal(std::vector<std::byte>(bytes.begin(), bytes.begin() + std::ptrdiff_t(n)), s.refs, into);
        ASSERT_NE(why, "") << "cut at " << n;
        ASSERT_NE(why.find("mergeDrawRecords: message 0"), std::string::npos) << why;
        ASSERT_EQ(into.size(), 1u) << "cut at " << n;
    }
    std::vector<std::byte> longer = bytes;
    longer.push_back(std::byte{0});
    EXPECT_NE(refusal(longer, s.refs, into).find("1 bytes after the last record"), std::string::npos);
}

// Records that do not fit this process (numbers it lacks, a NaN, weights or rows that do not
// fit, records out of order) are refused naming the record and the fault.
TEST(DrawRecords, RecordsThatDoNotFitAreRefusedByName) {
    Scene s;
    DrawList whole;
    const std::uint32_t all[] = {0, 1, 2, 3, 4, 5};
    fill(s, whole, all);
    const std::vector<std::byte> bytes = message(whole, s.refs);
    // Records of the list (offsets found by writing prefixes of it).
    std::vector<std::size_t> at;
    {
        DrawList prefix;
        DrawSegment& seg = prefix.segment(prefix.openSegments(1));
        for (const DrawItem& item : whole.items()) {
            if (item.actor == kNoActor) continue;
            at.push_back(message(prefix, s.refs).size());
            DrawItem& copy = seg.emplace(0, item.skinPaletteSize);
            const glm::mat4* palette = copy.skinPalette;
            copy = item;
            copy.skinPalette = palette;
            if (item.morphWeights) seg.addMorphWeights(copy, 2);
        }
    }
    ASSERT_EQ(at.size(), 10u);  // two items for actors 0, 1, 4 and 5, one for 2 (impostor) and 3 (key-pose)
    auto damaged = [&](std::size_t record, std::size_t offset, auto value) {
        std::vector<std::byte> b = bytes;
        std::memcpy(b.data() + at[record] + offset, &value, sizeof value);
        DrawList into;
        return refusal(b, s.refs, into);
    };
    // Head offsets (DrawRecords.cpp's RecordHead): translation 8, drawable 104, node 108,
    // source 112, weightCount 136, row 152, representation 162.
    EXPECT_NE(damaged(0, 104, std::uint32_t(3)).find("record 0 of 10: drawable 3 is not numbered here (3 are)"), std::string::npos);
    EXPECT_NE(damaged(1, 108, std::uint32_t(5)).find("record 1 of 10: node 5 is not numbered here"), std::string::npos);
    EXPECT_NE(damaged(4, 8, std::numeric_limits<double>::quiet_NaN()).find("not finite"), std::string::npos);
    EXPECT_NE(damaged(1, 136, std::uint32_t(1)).find("1 morph weights for a drawable of 2 morph targets"), std::string::npos);
    EXPECT_NE(damaged(5, 152, std::uint32_t(4)).find("in row 4 of a source of 10 poses and 4 rows"), std::string::npos);
    EXPECT_NE(damaged(4, 162, std::uint8_t(7)).find("representation 7 is none"), std::string::npos);
    EXPECT_NE(damaged(4, 112, std::uint32_t(0)).find("a key-pose source on an item that is not a key-pose"), std::string::npos);
    EXPECT_NE(damaged(9, 108, std::uint32_t(0)).find("record 9 of 10: out of order"), std::string::npos);
    EXPECT_NE(damaged(0, 168, std::numeric_limits<float>::infinity()).find("palette matrix or morph weight that is not finite"),
              std::string::npos);
    std::vector<std::byte> other = bytes;
    other[0] = std::byte{'X'};
    DrawList into;
    EXPECT_NE(refusal(other, s.refs, into).find("not draw records"), std::string::npos);
    std::vector<std::byte> many = bytes;
    const std::uint64_t count = 1'000'000'000'000ull;
    std::memcpy(many.data() + 4, &count, sizeof count);
    EXPECT_NE(refusal(many, s.refs, into).find("1000000000000 records announced"), std::string::npos);
}
