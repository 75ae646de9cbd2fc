// throng-town's ranks posing the walkers they step (RankPosing.h).

#include "RankPosing.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>

#include "RankWait.h"
#include "TownRun.h"
#include "throng/actors/ActorDrawReferences.h"
#include "throng/actors/Crowd.h"
#include "throng/scenegraph/ByteStream.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Drawable.h"
#include "throng/scenegraph/OcclusionBuffer.h"
#include "throng/sim/Locomotion.h"

namespace throng::town {
namespace {

// What rank 0 orders for one frame; its occlusion buffer follows when `occlusion` is 1.
struct FrameOrder {
    std::int64_t number = 0;        // the frame
    double time = 0.0;              // its simulation time (after the step)
    double cameraTime = 0.0;        // the camera path's time of its camera
    double aspect = 1.0;            // and aspect
    double view[16] = {}, projection[16] = {};  // the camera rank 0 culls with, to check the ranks' own
    double lodScale = 1.0;
    double impostorDistance = 0.0, impostorHysteresis = 0.0;
    double keyPoseDistance = 0.0, keyPoseHysteresis = 0.0;
    std::uint32_t occlusion = 0;    // 1: rank 0's buffer follows; 0: occlusion off or resting
    std::uint32_t padding = 0;
};

// What a rank sends rank 0 of one frame; its draw records follow.
struct ShareHead {
    ActorFrameStatistics stats;     // its APP and CULL
    std::uint64_t faceEvaluations[3] = {0, 0, 0};
    double faceSeconds = 0.0;
    double keyPoseWaitMs = 0.0;     // of its APP and CULL, waiting in the key-pose caches' exchanges
    std::uint64_t bytesSent = 0;    // bytes it sent in them (its demands), payloads and size headers
    std::uint64_t recordBytes = 0;  // bytes of draw records after the head
};

// One impostor of the set-up: the template (its index among the world's templates in use) and
// what a stand-in for it needs to be counted as rank 0's.
struct ImpostorStandIn {
    std::uint32_t templateIndex = 0;
    std::uint32_t morphTargets = 0;
    std::uint64_t primitives = 0;
    double bound[4] = {};  // centre, radius
};

void copyMatrix(const Mat4& m, double (&out)[16]) { std::memcpy(out, &m[0][0], sizeof out); }

// The outermost behaviour's slot-to-actor list of the walkers (empty when nothing walks).
std::span<const ActorId> walkerActors(const sim::Simulation& world) {
    const Crowd& crowd = world.crowd();
    for (const auto& g : world.groups()) {
        if (g.behaviour != "walk" || g.actors.empty()) continue;
        const Behaviour* outer = crowd.state().behaviour[g.actors.front()];
        for (std::size_t b = 0; b < crowd.behaviours().size(); ++b)
            if (crowd.behaviours()[b].get() == outer) return crowd.actorsBySlot(b);
    }
    return {};
}

}  // namespace

WalkerTiers::WalkerTiers(sim::Simulation& world) : walkers_(world.locomotion()), actorOfSlot_(walkerActors(world)) {}

void WalkerTiers::take(ActorProcessor& processor) const {
    const auto slots = walkers_ ? walkers_->presentSlots() : std::nullopt;
    if (!slots) return;
    for (const std::uint32_t slot : *slots) {
        const std::uint8_t c = walkers_->carried(slot);
        processor.setTiers(actorOfSlot_[slot], {std::uint8_t(c & 1u), std::uint8_t((c >> 1) & 1u)});
    }
}

void WalkerTiers::keep(const ActorProcessor& processor) {
    const auto slots = walkers_ ? walkers_->presentSlots() : std::nullopt;
    if (!slots) return;
    for (const std::uint32_t slot : *slots) {
        const ActorProcessor::ActorTiers t = processor.tiersOf(actorOfSlot_[slot]);
        walkers_->setCarried(slot, std::uint8_t(t.impostor | (t.keyPose << 1)));
    }
}

PosingRoot::PosingRoot(sim::Simulation& world, sim::Ranks& ranks, ActorProcessor& processor, double aspect)
    : world_(world), ranks_(ranks), processor_(processor), aspect_(aspect), arbiter_(ranks, kKeyPoseTag),
      refs_(actorDrawReferences(world.crowd(), world.root(), processor)), tiers_(world) {
    processor.setKeyPoseArbiter(&arbiter_);
    processor.setOcclusionSettledByShares(true);
    processor.setBeforeCull([this](const OcclusionBuffer* buffer) { sendOrders(buffer); });
}

sim::Bytes PosingRoot::setup() const {
    sim::Bytes bytes;
    ByteWriter out(bytes);
    out.put(std::uint32_t(processor_.keyPoseCaches().empty() ? 0 : 1));
    std::vector<ImpostorStandIn> impostors;
    const auto templates = world_.templates();
    for (std::size_t i = 0; i < templates.size(); ++i)
        if (const Drawable* d = processor_.impostorOf(*templates[i].tmpl)) {
            ImpostorStandIn s;
            s.templateIndex = std::uint32_t(i), s.morphTargets = d->morphTargetCount(), s.primitives = d->primitiveCount();
            for (int k = 0; k < 3; ++k) s.bound[k] = d->localBound().center()[k];
            s.bound[3] = d->localBound().radius();
            impostors.push_back(s);
        }
    out.put(std::uint32_t(impostors.size()));
    out.putSpan(std::span<const ImpostorStandIn>(impostors));
    return bytes;
}

void PosingRoot::beginFrame(std::int64_t number, double cameraTime) {
    number_ = number;
    bytesBefore_ = ranks_.bytesSent();
    cameraTime_ = cameraTime;
    tiers_.take(processor_);
}

void PosingRoot::sendOrders(const OcclusionBuffer* buffer) {
    FrameOrder o;
    o.number = number_, o.time = world_.now().time, o.cameraTime = cameraTime_, o.aspect = aspect_;
    const Camera camera = world_.camera().at(cameraTime_, aspect_);
    copyMatrix(camera.view(), o.view);
    copyMatrix(camera.projection(), o.projection);
    o.lodScale = processor_.lodScale();
    o.impostorDistance = processor_.impostorDistance(), o.impostorHysteresis = processor_.impostorHysteresis();
    o.keyPoseDistance = processor_.keyPoseDistance(), o.keyPoseHysteresis = processor_.keyPoseHysteresis();
    o.occlusion = buffer ? 1 : 0;
    orders_.clear();
    ByteWriter out(orders_);
    out.put(o);
    if (buffer) buffer->write(out);
    ranks_.broadcast(orders_, kFrameOrderTag, "frame orders");
}

void PosingRoot::finishFrame(PreparedFrame& f, const FaceTally::Counts& mine) {
    tiers_.keep(processor_);
    mine_.clear();
    writeDrawRecords(processor_.drawList(), refs_, mine_);
    const std::vector<sim::Bytes> shares = ranks_.gather({}, kShareTag, "frame shares");
    // Rank 0's items of the scene itself first (generic CULL lists them before any actor's), then
    // every rank's actors in the order one process lists them.
    f.merged.clear();
    for (const DrawItem& item : processor_.drawList().items())
        if (item.actor == kNoActor) f.merged.add(item, item.drawable->primitiveCount());
    messages_.assign(1, std::span<const std::byte>(mine_));
    f.posed.assign(shares.size(), {});
    f.posed[0] = {f.stats.drawItems - f.merged.size(), ranks_.bytesSent() - bytesBefore_, f.stats.appCullMs(), arbiter_.takeWaitMs()};
    for (int k = 0; k < 3; ++k) f.faceEvaluations[k] = mine.evaluations[k];
    double faceSeconds = mine.seconds;
    for (std::size_t r = 1; r < shares.size(); ++r) {
        ByteReader in(shares[r], "rank 0 reading rank " + std::to_string(r) + "'s share of frame " + std::to_string(f.number));
        ShareHead head;
        try {
            head = in.get<ShareHead>("the share's statistics");
            messages_.push_back(in.take(head.recordBytes, "the share's draw records"));
            if (in.remaining() != 0) throw std::invalid_argument(in.source() + ": " + std::to_string(in.remaining()) + " bytes after the draw records");
        } catch (const std::invalid_argument& e) {
            throw sim::RankError(int(r), e.what());
        }
        addShare(f.stats, head.stats);
        f.posed[r] = {head.stats.drawItems, head.bytesSent + shares[r].size() + sizeof(std::uint64_t), head.stats.appCullMs(), head.keyPoseWaitMs};
        for (int k = 0; k < 3; ++k) f.faceEvaluations[k] += head.faceEvaluations[k];
        faceSeconds += head.faceSeconds;
    }
    f.faceMs = 1000.0 * faceSeconds;
    try {
        merger_.merge(messages_, refs_, f.merged);
    } catch (const std::invalid_argument& e) {
        throw std::runtime_error(std::string("the ranks' draw records of frame ") + std::to_string(f.number) +
                                 " do not fit rank 0's world (message k is rank k's): " + e.what());
    }
    f.list = &f.merged;
    processor_.settleOcclusion(f.stats);
}

int poseShare(sim::Simulation& world, sim::Ranks& ranks, const TownOptions& o) {
    const std::string label = " (rank " + std::to_string(ranks.rank()) + ")";
    try {
        world.setThreads(unsigned(o.threads));
        ActorProcessor processor(world.crowd());
        processor.setProcessing(Processing::Actor);
        processor.setThreads(unsigned(o.threads));
        // Rank 0's set-up comes with its start signal (after it baked its impostors).
        const sim::Bytes setup = waitLong(ranks, [&] { return ranks.broadcast({}, kStartTag, "start"); });
        sim::RankKeyPoseArbiter arbiter(ranks, kKeyPoseTag);
        try {
            ByteReader in(setup, "the set-up rank 0 sent");
            if (in.get<std::uint32_t>("whether key-pose caches are attached")) {
                world.attachKeyPoseCaches(processor);
                processor.setKeyPoseArbiter(&arbiter);
            }
            const auto count = in.get<std::uint32_t>("the number of impostors");
            const auto templates = world.templates();
            for (std::uint32_t i = 0; i < count; ++i) {
                const auto s = in.get<ImpostorStandIn>("an impostor");
                if (s.templateIndex >= templates.size())
                    throw std::invalid_argument("an impostor of template " + std::to_string(s.templateIndex) + " of " +
                                                std::to_string(templates.size()));
                // Numbered and counted as rank 0's impostor; only rank 0 draws it.
                const BoundingSphere bound(Vec3(s.bound[0], s.bound[1], s.bound[2]), s.bound[3]);
                processor.setImpostor(*templates[s.templateIndex].tmpl,
                                      std::make_shared<Drawable>("impostor of " + templates[s.templateIndex].name, bound, s.primitives, s.morphTargets));
            }
            if (in.remaining() != 0) throw std::invalid_argument(std::to_string(in.remaining()) + " bytes after the impostors");
        } catch (const std::invalid_argument& e) {
            throw sim::RankError(0, std::string("rank 0's set-up cannot be read: ") + e.what());
        }
        const DrawReferences refs = actorDrawReferences(world.crowd(), world.root(), processor);
        WalkerTiers tiers(world);
        FaceTally faces;
        // Rank 0's occlusion buffer, of the size the scene declares.
        std::optional<OcclusionBuffer> buffer;
        if (const auto& occlusion = world.description().representation.occlusion) buffer.emplace(occlusion->width, occlusion->height);
        sim::Bytes share;
        for (std::int64_t f = 0; f < o.frames; ++f) {
            world.step();
            const sim::Bytes bytes = ranks.broadcast({}, kFrameOrderTag, "frame orders");
            FrameOrder order;
            try {
                ByteReader in(bytes, "the orders of frame " + std::to_string(f) + " rank 0 sent");
                order = in.get<FrameOrder>("the orders");
                if (order.occlusion && !buffer) throw std::invalid_argument("an occlusion buffer, though the scene declares no occlusion");
                if (order.occlusion) buffer->read(in);
                if (in.remaining() != 0) throw std::invalid_argument(std::to_string(in.remaining()) + " bytes after the orders");
            } catch (const std::invalid_argument& e) {
                throw sim::RankError(0, e.what());
            }
            // Rank 0's frame and camera must be this rank's: every rank steps the same clock and
            // follows the same camera path.
            const Camera camera = world.camera().at(order.cameraTime, order.aspect);
            double view[16], projection[16];
            copyMatrix(camera.view(), view);
            copyMatrix(camera.projection(), projection);
            if (order.number != f || order.time != world.now().time || std::memcmp(view, order.view, sizeof view) != 0 ||
                std::memcmp(projection, order.projection, sizeof projection) != 0)
                throw sim::RankError(0, "rank 0 ordered frame " + std::to_string(order.number) + " at " + std::to_string(order.time) +
                                            " s with another camera; this rank is at frame " + std::to_string(f) + ", " +
                                            std::to_string(world.now().time) + " s");
            processor.setLodScale(order.lodScale);
            processor.setImpostorDistance(order.impostorDistance, order.impostorHysteresis);
            processor.setKeyPoseDistance(order.keyPoseDistance, order.keyPoseHysteresis);
            processor.setSharedOcclusionBuffer(order.occlusion ? &*buffer : nullptr);
            tiers.take(processor);
            const std::size_t bytesBefore = ranks.bytesSent();
            ShareHead head;
            head.stats = processor.processFrame(world.root(), camera, world.now().time);
            tiers.keep(processor);
            const FaceTally::Counts counts = faces.take(world);
            for (int k = 0; k < 3; ++k) head.faceEvaluations[k] = counts.evaluations[k];
            head.faceSeconds = counts.seconds;
            head.keyPoseWaitMs = arbiter.takeWaitMs();
            head.bytesSent = ranks.bytesSent() - bytesBefore;
            share.clear();
            ByteWriter out(share);
            out.put(head);  // written again below, once the records' size is known
            writeDrawRecords(processor.drawList(), refs, share);
            head.recordBytes = share.size() - sizeof head;
            std::memcpy(share.data(), &head, sizeof head);
            ranks.gather(share, kShareTag, "frame shares");
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "throng-town%s: %s\n", label.c_str(), e.what());
        ranks.abort(3);
    }
    return 0;
}

}  // namespace throng::town
