// Phase 7 of actor processing: the draw list (see DrawListJob.h).

#include "../ActorDrawItem.h"
#include "HeldObjects.h"
#include "throng/actors/cascade/DrawListJob.h"
#include "throng/scenegraph/Transform.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/actors/detail/PoseKernels.h"
#include "throng/scenegraph/Drawable.h"

namespace throng::cascade {
namespace {

const Drawable* impostorOf(const Settings& settings, const ActorTemplate& tmpl) {
    for (const auto& [t, d] : *settings.impostors)
        if (t == &tmpl) return d.get();
    return nullptr;
}

// Appends the item drawing `d` for part `part` of the actor `a`, written in place and counted; the
// caller places it.
DrawItem& emit(ChunkOutput& out, const detail::ActorItemBase& a, const Drawable& d, std::uint32_t part, int level,
               std::size_t paletteSize = 0, Representation representation = Representation::Mesh) {
    ++out.counts.drawItems;
    out.counts.primitives += d.primitiveCount();
    return detail::addActorPart(*out.items, a, d, part, level, paletteSize, representation);
}

// The items of posed actor j (its index among the posed).
void emitPosed(const DrawListJob& job, ChunkOutput& out, std::size_t j, const detail::ActorItemBase& a, OpTally* nodeOps) {
    const Crowd::State& s = *job.crowd;
    const PosedActors& p = *job.posed;
    const InternalVisibility& v = *job.visibility;
    const Candidate& cand = job.candidates[job.survivors[p.posed[j]]];
    const ActorId id = cand.id;
    const ActorTemplate& t = *s.tmpl[id];
    const std::size_t n = t.nodeCount();
    const std::uint32_t base = p.nodeBase[j];
    const std::span<const std::uint8_t> active(p.active.data() + base, n);
    const std::span<const Affine> model(p.model.data() + base, n);
    const Mat4& skls = s.sklsWorld[id];
    const double d2 = job.decisions->detail2[p.posed[j]];
    const bool all = v.visibility[j] == kAllVisible;
    const auto self = static_cast<std::uint32_t>(n);  // the part number of the actor-level geometry
    const int rootLevel = t.rootGeometry().selectSquared(d2);
    if (rootLevel >= 0 && (all || v.rootVisible[j])) {
        const VaLodLevel& lv = t.rootGeometry().levels()[static_cast<std::size_t>(rootLevel)];
        if (lv.drawable && lv.skin >= 0) {  // the palette is computed straight into the list
            const Skin& skin = t.skins()[static_cast<std::size_t>(lv.skin)];
            DrawItem& item = emit(out, a, *lv.drawable, self, rootLevel, skin.joints.size());
            item.world = ItemTransform(skls);
            computeSkinPalette(t, skin, model, active, DrawSegment::paletteRoom(item), nodeOps);
        } else if (lv.drawable) {
            emit(out, a, *lv.drawable, self, rootLevel).world = ItemTransform(skls);
        }
    }
    const auto tnodes = t.nodes();
    for (std::size_t i = 0; i < n; ++i) {
        if (!active[i]) {
            i = t.subtreeEnd(i) - 1;
            continue;
        }
        if (!all && !v.visible[base + i]) continue;
        const int level = tnodes[i].geometry.selectSquared(d2);
        if (level < 0) continue;
        const auto& d = tnodes[i].geometry.levels()[static_cast<std::size_t>(level)].drawable;
        if (!d) continue;
        // The part's world transform is composed once, straight into its item.
        detail::nodeWorldTransform(skls, model[i], emit(out, a, *d, static_cast<std::uint32_t>(i), level).world, nodeOps);
    }
    if (s.held[id] < 0) return;
    const auto& held = s.heldObjects[static_cast<std::size_t>(s.held[id])];
    for (std::uint32_t k = 0; k < held.size(); ++k) {
        const int holder = holderNode(t, active, held[k].node);
        const Mat4 world = holder < 0 ? skls : composeAffine(skls, model[static_cast<std::size_t>(holder)].toDMat4(), nodeOps);
        if (!all) {
            if (holder >= 0 && v.masks[base + static_cast<std::size_t>(holder)] == kCulled) continue;
            PlaneMask m = holder < 0 ? cand.mask : v.masks[base + static_cast<std::size_t>(holder)];
            ++out.counts.spheresTested;
            if (job.frustum->classify(held[k].drawable->localBound().transformed(world), m) == Containment::Outside) continue;
        }
        emit(out, a, *held[k].drawable, self + 1 + k, 0).world = ItemTransform(world);
    }
}

// The item of an actor drawn from its template's key-pose cache: the skinned mesh of its vaLod
// level, placed by its Skeleton Root, its vertices read from the cache rows `ref` names.
void emitCached(const DrawListJob& job, ChunkOutput& out, std::size_t survivor, const detail::ActorItemBase& a) {
    const Crowd::State& s = *job.crowd;
    const ActorTemplate& t = *s.tmpl[a.id];
    const int level = t.rootGeometry().selectSquared(job.decisions->detail2[survivor]);
    if (level < 0) return;
    const VaLodLevel& lv = t.rootGeometry().levels()[static_cast<std::size_t>(level)];
    if (!lv.drawable) return;
    const std::uint32_t part = static_cast<std::uint32_t>(t.nodeCount());
    DrawItem& item = emit(out, a, *lv.drawable, part, level, 0, lv.skin >= 0 ? Representation::KeyPose : Representation::Mesh);
    item.world = ItemTransform(s.sklsWorld[a.id]);
    if (lv.skin >= 0) {
        item.keyPose = job.decisions->keyPoseOf[survivor];
        item.keyPose.skin = static_cast<std::uint32_t>(lv.skin);
    }
}

}  // namespace

const char* DrawListJob::problem(const PhaseLoop& loop) const {
    if (!loop.drawing()) return "the loop has no draw list";
    if (!crowd || !frustum || !settings || !decisions || !posed || !visibility)
        return "crowd, frustum, settings, decisions, posed and visibility are required";
    if (survivors.size() > candidates.size()) return "more survivors than candidates";
    if (decisions->outcome.size() != survivors.size() || decisions->detail2.size() != survivors.size())
        return "the decisions must have one entry per survivor";
    const PosedActors& p = *posed;
    if (p.posedOf.size() != p.shown.size() || p.nodeBase.size() != p.posed.size() || p.model.size() != p.active.size())
        return "the posed actors' arrays disagree in size";
    if (visibility->visibility.size() != p.posed.size() || visibility->rootVisible.size() != p.posed.size() ||
        visibility->visible.size() != p.active.size() || visibility->masks.size() != p.active.size())
        return "the visibility does not match the posed actors";
    return nullptr;
}

void DrawListJob::run(PhaseLoop& loop) const {
    throwIfInvalid("DrawListJob", loop.ready() ? problem(loop) : "the loop has no frame");
    const Crowd::State& s = *crowd;
    const PosedActors& p = *posed;
    loop.parallelDrawing(p.shown.size(), kHeavyGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        OpTally* nodeOps = tallyFor(loop.counterOf(out), OpCategory::SkeletonMatrix);
        for (std::size_t k = begin; k < end; ++k) {
            const std::uint32_t j = p.posedOf[k];
            if (j != PosedActors::kNotPosed && visibility->visibility[j] == kNoneVisible) continue;
            const Candidate& cand = candidates[survivors[p.shown[k]]];
            const detail::ActorItemBase a = detail::actorItemBase(s, cand.id, cand.node, cand.member, time);
            if (j != PosedActors::kNotPosed) {
                emitPosed(*this, out, j, a, nodeOps);
                continue;
            }
            if (decisions->outcome[p.shown[k]] == kCached) {
                emitCached(*this, out, p.shown[k], a);
                continue;
            }
            // An impostor: one item at the Reference Point, no Skeleton node processed.
            const ActorTemplate& t = *s.tmpl[cand.id];
            const Drawable* impostor = impostorOf(*settings, t);
            if (!impostor) continue;  // decided by other settings: nothing to draw it with
            emit(out, a, *impostor, static_cast<std::uint32_t>(t.nodeCount()), 0, 0, Representation::Impostor).world =
                ItemTransform(s.refWorld[cand.id]);
        }
    });
}

}  // namespace throng::cascade
