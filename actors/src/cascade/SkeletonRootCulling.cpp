// Phase 4 of actor processing, CULL 2: Sklsroot Bspheres of actors whose Refpoint Bsphere crosses
// a plane, then every survivor's Sklsroot Bsphere against the occlusion buffer (when there is one); one eye distance per actor that passes (every later LOD decision reads it); the hybrid
// tier (impostor or geometry, with hysteresis); the behavioural level and skeletal LOD of the
// actors that keep their geometry.

#include <algorithm>
#include <cmath>

#include "CascadeFrame.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/KeyPoseCache.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/scenegraph/OcclusionBuffer.h"
#include "throng/scenegraph/Stopwatch.h"

namespace throng::cascade {
namespace {

// The Sklsroot Bsphere is tested against the occlusion buffer after CULL 2 only when its radius is
// below this share of the Refpoint Bsphere's.
constexpr double kSecondOcclusionTest = 0.75;

// Updates a tier flag kept across frames at squared detail distance `detail2`: it is set beyond
// distance + hysteresis and cleared within distance - hysteresis, so actors near the threshold do
// not flicker; true while set. Squared distances: no square root per actor.
bool beyondWithHysteresis(std::uint8_t& tier, double detail2, double distance, double hysteresis) {
    const double out = distance + hysteresis;
    const double in = std::max(distance - hysteresis, 0.0);
    if (tier != 0 && detail2 < in * in) tier = 0;
    else if (tier == 0 && detail2 > out * out) tier = 1;
    return tier != 0;
}

// Updates the hybrid tier of actor `id` at squared detail distance `detail2`; true while it is an
// impostor.
bool impostorTier(const CascadeFrame& f, ActorId id, const ActorTemplate& tmpl, double detail2) {
    std::uint8_t& tier = (*f.impostorTier)[id];
    const Drawable* impostor = nullptr;
    for (const auto& [t, d] : *f.settings.impostors)
        if (t == &tmpl) impostor = d.get();
    if (!impostor) return tier = 0, false;
    return beyondWithHysteresis(tier, detail2, f.settings.impostorDistance, f.settings.impostorHysteresis);
}

// The key-pose cache of `tmpl`, as its index in the settings, or -1.
int cacheOf(const CascadeFrame& f, const ActorTemplate& tmpl) {
    const auto& caches = *f.settings.keyPoseCaches;
    for (std::size_t i = 0; i < caches.size(); ++i)
        if (&caches[i]->actorTemplate() == &tmpl) return static_cast<int>(i);
    return -1;
}

// Updates the key-pose tier of actor `id` (the band beyond the key-pose distance); true while in it.
bool keyPoseBand(const CascadeFrame& f, ActorId id, double detail2) {
    return beyondWithHysteresis((*f.keyPoseTier)[id], detail2, f.settings.keyPoseDistance, f.settings.keyPoseHysteresis);
}

}  // namespace

void cullSkeletonRoots(CascadeFrame& f) {
    Crowd::State& s = f.crowd->state();
    const std::size_t n = f.survivors.size();
    f.outcome.resize(n);
    f.detail2.resize(n);
    f.level.resize(n);
    if (f.impostorTier->size() < f.crowd->size()) f.impostorTier->resize(f.crowd->size(), 0);
    const bool impostors = f.settings.impostorDistance > 0.0;
    const bool caches = f.settings.keyPoseDistance > 0.0 && f.settings.keyPoseCaches && !f.settings.keyPoseCaches->empty();
    if (caches) {
        if (f.keyPoseTier->size() < f.crowd->size()) f.keyPoseTier->resize(f.crowd->size(), 0);
        f.cacheOf.resize(n);
        f.keyPoseOf.resize(n);
    }
    f.parallel(n, kLightGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        OpCounter* c = f.counterOf(out);
        OpTally* testOps = tallyFor(c, OpCategory::BsphereFrustumTest);
        OpTally* lodOps = tallyFor(c, OpCategory::LodDistance);
        ActorFrameStatistics& counts = out.counts;
        for (std::size_t k = begin; k < end; ++k) {
            Candidate& cand = f.candidates[f.survivors[k]];
            const ActorId id = cand.id;
            if (cand.stage == kCrossing) {
                const BoundingSphere skls(Vec3(s.sklsWorld[id][3]), s.sklsRadius[id]);
                ++counts.spheresTested;
                countOperations(c, OpCategory::BsphereFrustumTest);
                const Containment r = f.frustum.classify(skls, cand.mask, testOps);
                if (r == Containment::Outside) {
                    s.actorClass[id] = ActorClass::C1;
                    ++counts.c1;
                    f.outcome[k] = kRejected;
                    continue;
                }
                s.actorClass[id] = r == Containment::Inside ? ActorClass::C2 : ActorClass::C3_1;  // C3 refined in phase 6
                if (r == Containment::Inside) ++counts.c2;
            } else {
                s.actorClass[id] = ActorClass::B;
                ++counts.b;
            }
            // Occlusion again only where the Sklsroot Bsphere is much smaller than the Refpoint
            // Bsphere that was just found visible: a sphere nearly as large rarely hides now.
            if (f.occlusion && s.sklsRadius[id] < kSecondOcclusionTest * s.refSphereWorld[id].radius()) {
                ++counts.occlusionTests;
                if (f.occlusion->occluded(BoundingSphere(Vec3(s.sklsWorld[id][3]), s.sklsRadius[id]))) {
                    // Undo the class counted above: the actor leaves the cascade here.
                    if (s.actorClass[id] == ActorClass::B) --counts.b;
                    else if (s.actorClass[id] == ActorClass::C2) --counts.c2;
                    s.actorClass[id] = ActorClass::Occluded;
                    ++counts.occludedSklsroot;
                    f.outcome[k] = kRejected;
                    continue;
                }
            }
            // The actor's one eye distance.
            const double d2 = detailDistanceSquared(s.sklsWorld[id], f.eye, f.settings.lodScale2, s.priority[id], lodOps);
            s.eyeDistance[id] = eyeDistance(s.sklsWorld[id], f.eye, lodOps);
            countOperations(c, OpCategory::LodDistance);
            ++counts.lodDistances;
            ++counts.eyeDistances;
            f.detail2[k] = d2;
            const ActorTemplate& t = *s.tmpl[id];
            if (impostors && impostorTier(f, id, t, d2)) {
                f.outcome[k] = kImpostor;
                ++counts.impostors;
                continue;
            }
            f.outcome[k] = kPosed;
            f.level[k] = f.settings.behaviouralLod ? s.behaviour[id]->levelFor(std::sqrt(d2)) : 0;
            // In a key-pose cache's band (and holding nothing a cache cannot show): the poses it
            // needs; selectKeyPoses decides whether the cache holds them.
            if (!caches || s.held[id] >= 0) continue;
            const int cache = cacheOf(f, t);
            if (cache < 0 || !keyPoseBand(f, id, d2)) continue;
            const Behaviour& behaviour = *s.behaviour[id];
            const int clip = behaviour.mainClip(s.slot[id]);
            if (clip < 0) continue;
            const KeyPoseCache& kc = *(*f.settings.keyPoseCaches)[static_cast<std::size_t>(cache)];
            const KeyPoseSample sample = kc.sample(clip, behaviour.clipTime(s.slot[id], f.context.time));
            f.outcome[k] = kCached;
            f.cacheOf[k] = static_cast<std::uint16_t>(cache);
            KeyPoseRef& ref = f.keyPoseOf[k];
            ref = KeyPoseRef{};
            ref.source = &kc;
            ref.pose[0] = sample.a;
            ref.pose[1] = sample.b;
            ref.blend = sample.blend;
            ++counts.keyPoseBand;
        }
    });
    if (caches) {
        Stopwatch watch;
        selectKeyPoses(f);
        f.stats->keyPoseSelectMs += watch.elapsedMs();
    }

    // The actors shown, in candidate order; the posed ones get their room in the per-node arrays.
    f.shown.clear();
    f.posedOf.clear();
    f.posed.clear();
    f.nodeBase.clear();
    std::uint32_t nodes = 0;
    for (std::uint32_t k = 0; k < n; ++k) {
        if (f.outcome[k] == kRejected) continue;
        f.shown.push_back(k);
        if (f.outcome[k] == kImpostor || f.outcome[k] == kCached) {
            f.posedOf.push_back(CascadeFrame::kNotPosed);
            continue;
        }
        f.posedOf.push_back(static_cast<std::uint32_t>(f.posed.size()));
        f.level[f.posed.size()] = f.level[k];  // compacted in place: posed index <= survivor index
        f.posed.push_back(k);
        f.nodeBase.push_back(nodes);
        nodes += static_cast<std::uint32_t>(s.tmpl[f.candidates[f.survivors[k]].id]->nodeCount());
    }
    f.level.resize(f.posed.size());
    f.active.resize(nodes);
    f.model.resize(nodes);

    // Skeletal LOD: which Skeleton nodes each posed actor keeps.
    f.parallel(f.posed.size(), kLightGrain, [&](ChunkOutput&, std::size_t begin, std::size_t end) {
        for (std::size_t j = begin; j < end; ++j) {
            const ActorTemplate& t = *s.tmpl[f.candidates[f.survivors[f.posed[j]]].id];
            const std::span<std::uint8_t> active(f.active.data() + f.nodeBase[j], t.nodeCount());
            if (f.settings.skeletalLod) computeActiveNodes(t, f.detail2[f.posed[j]], active);
            else std::fill(active.begin(), active.end(), std::uint8_t{1});
        }
    });
}

}  // namespace throng::cascade
