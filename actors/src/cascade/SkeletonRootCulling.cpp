// Phase 4 of actor processing, CULL 2 (see SkeletonRootCullingJob.h).

#include <algorithm>
#include <cmath>

#include "throng/actors/KeyPoseCache.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/actors/cascade/SkeletonRootCullingJob.h"
#include "throng/scenegraph/OcclusionBuffer.h"

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

// Updates the hybrid tier `tier` of an actor of `tmpl` at squared detail distance `detail2`; true
// while it is an impostor.
bool updateImpostorTier(const Settings& settings, std::uint8_t& tier, const ActorTemplate& tmpl, double detail2) {
    const Drawable* impostor = nullptr;
    for (const auto& [t, d] : *settings.impostors)
        if (t == &tmpl) impostor = d.get();
    if (!impostor) return tier = 0, false;
    return beyondWithHysteresis(tier, detail2, settings.impostorDistance, settings.impostorHysteresis);
}

// The key-pose cache of `tmpl`, as its index in the settings, or -1.
int cacheOf(const Settings& settings, const ActorTemplate& tmpl) {
    const auto& caches = *settings.keyPoseCaches;
    for (std::size_t i = 0; i < caches.size(); ++i)
        if (&caches[i]->actorTemplate() == &tmpl) return static_cast<int>(i);
    return -1;
}

}  // namespace

const char* SkeletonRootCullingJob::problem() const {
    if (!crowd || !frustum || !settings || !impostorTier || !keyPoseTier || !decisions)
        return "crowd, frustum, settings, both tiers and decisions are required";
    const std::size_t n = crowd->tmpl.size();
    if (actorClass.size() != n || eyeDistance.size() != n) return "actorClass and eyeDistance must have one entry per actor";
    if (survivors.size() > candidates.size()) return "more survivors than candidates";
    return nullptr;
}

void SkeletonRootCullingJob::run(PhaseLoop& loop) const {
    throwIfInvalid("SkeletonRootCullingJob", loop.ready() ? problem() : "the loop has no frame");
    const Crowd::State& s = *crowd;
    SurvivorDecisions& d = *decisions;
    const std::size_t n = survivors.size();
    d.outcome.resize(n);
    d.detail2.resize(n);
    d.level.resize(n);
    if (impostorTier->size() < s.tmpl.size()) impostorTier->resize(s.tmpl.size(), 0);
    const bool impostors = settings->impostorsOn();
    const bool caches = settings->keyPoseCachesOn();
    if (caches) {
        if (keyPoseTier->size() < s.tmpl.size()) keyPoseTier->resize(s.tmpl.size(), 0);
        d.cacheOf.resize(n);
        d.keyPoseOf.resize(n);
    }
    loop.parallel(n, kLightGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        OpCounter* c = loop.counterOf(out);
        OpTally* testOps = tallyFor(c, OpCategory::BsphereFrustumTest);
        OpTally* lodOps = tallyFor(c, OpCategory::LodDistance);
        ActorFrameStatistics& counts = out.counts;
        for (std::size_t k = begin; k < end; ++k) {
            Candidate& cand = candidates[survivors[k]];
            const ActorId id = cand.id;
            if (cand.stage == kCrossing) {
                const BoundingSphere skls(Vec3(s.sklsWorld[id][3]), s.sklsRadius[id]);
                ++counts.spheresTested;
                countOperations(c, OpCategory::BsphereFrustumTest);
                const Containment r = frustum->classify(skls, cand.mask, testOps);
                if (r == Containment::Outside) {
                    actorClass[id] = ActorClass::C1;
                    ++counts.c1;
                    d.outcome[k] = kRejected;
                    continue;
                }
                actorClass[id] = r == Containment::Inside ? ActorClass::C2 : ActorClass::C3_1;  // C3 refined in phase 6
                if (r == Containment::Inside) ++counts.c2;
            } else {
                actorClass[id] = ActorClass::B;
                ++counts.b;
            }
            // Occlusion again only where the Sklsroot Bsphere is much smaller than the Refpoint
            // Bsphere that was just found visible: a sphere nearly as large rarely hides now.
            if (occlusion && s.sklsRadius[id] < kSecondOcclusionTest * s.refSphereWorld[id].radius()) {
                ++counts.occlusionTests, ++counts.occlusionObjectsTested;
                if (occlusion->occluded(BoundingSphere(Vec3(s.sklsWorld[id][3]), s.sklsRadius[id]))) {
                    // Undo the class counted above: the actor leaves the cascade here.
                    if (actorClass[id] == ActorClass::B) --counts.b;
                    else if (actorClass[id] == ActorClass::C2) --counts.c2;
                    actorClass[id] = ActorClass::Occluded;
                    ++counts.occludedSklsroot;
                    d.outcome[k] = kRejected;
                    continue;
                }
            }
            // The actor's one eye distance.
            const double d2 = detailDistanceSquared(s.sklsWorld[id], eye, settings->lodScale2, s.priority[id], lodOps);
            eyeDistance[id] = throng::eyeDistance(s.sklsWorld[id], eye, lodOps);
            countOperations(c, OpCategory::LodDistance);
            ++counts.lodDistances;
            ++counts.eyeDistances;
            d.detail2[k] = d2;
            const ActorTemplate& t = *s.tmpl[id];
            if (impostors && updateImpostorTier(*settings, (*impostorTier)[id], t, d2)) {
                d.outcome[k] = kImpostor;
                ++counts.impostors;
                continue;
            }
            d.outcome[k] = kPosed;
            d.level[k] = settings->behaviouralLod ? s.behaviour[id]->levelFor(std::sqrt(d2)) : 0;
            // In a key-pose cache's band (and holding nothing a cache cannot show): the poses it
            // needs; KeyPoseSelectingJob decides whether the cache holds them.
            if (!caches || s.held[id] >= 0) continue;
            const int cache = cacheOf(*settings, t);
            if (cache < 0 ||
                !beyondWithHysteresis((*keyPoseTier)[id], d2, settings->keyPoseDistance, settings->keyPoseHysteresis))
                continue;
            const Behaviour& behaviour = *s.behaviour[id];
            const int clip = behaviour.mainClip(s.slot[id]);
            if (clip < 0) continue;
            const KeyPoseCache& kc = *(*settings->keyPoseCaches)[static_cast<std::size_t>(cache)];
            const KeyPoseSample sample = kc.sample(clip, behaviour.clipTime(s.slot[id], time));
            d.outcome[k] = kCached;
            d.cacheOf[k] = static_cast<std::uint16_t>(cache);
            KeyPoseRef& ref = d.keyPoseOf[k];
            ref = KeyPoseRef{};
            ref.source = &kc;
            ref.pose[0] = sample.a;
            ref.pose[1] = sample.b;
            ref.blend = sample.blend;
            ++counts.keyPoseBand;
        }
    });
}

}  // namespace throng::cascade
