// libFuzzer entry point: any bytes as the messages ranks send each other about a frame. The first
// byte chooses what reads them: draw records (up to three messages, split where the next two
// bytes say) merged into a list holding one item, or an occlusion buffer. Each must either be read
// or throw std::invalid_argument; a refused merge must leave the list as it was.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <stdexcept>
#include <vector>

#include "throng/scenegraph/ByteStream.h"
#include "throng/scenegraph/DrawRecords.h"
#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/OcclusionBuffer.h"

namespace {

// A source of 4 rows over 10 poses.
class FourRows : public throng::KeyPoseSource {
public:
    std::uint32_t rowCount() const override { return 4; }
    std::uint32_t poseCount() const override { return 10; }
    std::span<const glm::mat4> palette(std::uint32_t, std::uint32_t) const override { return {}; }
};

// What the reading process numbers: two nodes, three drawables (one with two morph targets), one
// key-pose source (as the corpus's messages were written against).
struct Numbered {
    throng::Group first, second;
    throng::Drawable body{"body", throng::BoundingSphere(throng::Vec3(0.0), 1.0), 100};
    throng::Drawable face{"face", throng::BoundingSphere(throng::Vec3(0.0), 0.2), 40, 2};
    throng::Drawable impostor{"impostor", throng::BoundingSphere(throng::Vec3(0.0), 1.0), 2};
    FourRows rows;
    throng::DrawReferences refs;
    Numbered() {
        refs.addNode(first), refs.addNode(second);
        refs.addDrawable(body), refs.addDrawable(face), refs.addDrawable(impostor);
        refs.addKeyPoseSource(rows);
    }
};

void mergeRecords(std::span<const std::byte> bytes) {
    static Numbered numbered;
    static throng::DrawRecordMerger merger;
    // Up to three messages: the first two bytes give the first two lengths (in 64-byte steps).
    std::vector<std::span<const std::byte>> messages;
    std::size_t at = 2;
    for (int m = 0; m < 2 && bytes.size() >= 2; ++m) {
        const std::size_t length = std::min(bytes.size() - std::min(at, bytes.size()), std::size_t(std::to_integer<unsigned>(bytes[m])) * 64);
        if (at >= bytes.size()) break;
        messages.push_back(bytes.subspan(at, length));
        at += length;
    }
    if (at < bytes.size()) messages.push_back(bytes.subspan(at));
    throng::DrawList list;
    throng::DrawItem street;
    street.drawable = &numbered.body;
    list.add(street, 100);
    try {
        merger.merge(messages, numbered.refs, list);
    } catch (const std::invalid_argument&) {
        if (list.size() != 1 || list.primitiveCount() != 100) std::abort();  // a refused merge changed the list
        return;
    }
    bool first = true;  // the street, which has no node
    for (const throng::DrawItem& item : list.items()) {
        if (!item.drawable || (!first && !item.node)) std::abort();  // a merged item points nowhere
        first = false;
    }
}

void readBuffer(std::span<const std::byte> bytes) {
    static throng::OcclusionBuffer buffer(16, 9);
    throng::ByteReader in(bytes, "fuzz");
    try {
        buffer.read(in);
    } catch (const std::invalid_argument&) {
        return;
    }
    (void)buffer.occluded(throng::BoundingSphere(throng::Vec3(0.0, 0.0, -10.0), 1.0));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::span<const std::byte> rest(reinterpret_cast<const std::byte*>(data) + 1, size - 1);
    if (data[0] % 2 == 0) mergeRecords(rest);
    else readBuffer(rest);
    return 0;
}
