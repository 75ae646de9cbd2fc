#pragma once
// Internal to actors: phase 1 over a range of actors, as both processing methods run it. Each
// behaviour is asked for the Reference Points of up to kRun consecutive actors it drives at once
// (Behaviour::referencePoints), so one virtual call serves many actors and a behaviour can share
// work between them; every actor gets the bits a call of its own would give.

#include <cstddef>
#include <cstdint>

#include "throng/actors/Crowd.h"

namespace throng::detail {

/// Writes the local Reference Point of actors idOf(begin) … idOf(end - 1) into s.refLocal, and
/// whether each is present into s.present; an absent actor's is not computed (its state here is
/// stale, and nothing of this frame reads it). The actors of a behaviour for which
/// `presentByList(behaviour)` is true are present without asking (its list named them).
template <class IdOf, class PresentByList>
void computeReferencePointRuns(Crowd::State& s, std::size_t begin, std::size_t end, IdOf&& idOf, const FrameContext& context,
                               OpTally* ops, PresentByList&& presentByList) {
    constexpr std::size_t kRun = 32;
    std::uint32_t slots[kRun];
    ActorId ids[kRun];
    std::uint8_t present[kRun];
    Mat4 out[kRun];
    for (std::size_t k = begin; k < end;) {
        Behaviour* behaviour = s.behaviour[idOf(k)];
        std::size_t n = 0;
        bool consecutive = true;  // ids[j] = ids[0] + j: the matrices go straight into place
        for (; n < kRun && k + n < end; ++n) {
            const ActorId id = idOf(k + n);
            if (s.behaviour[id] != behaviour) break;
            ids[n] = id;
            slots[n] = s.slot[id];
            consecutive = consecutive && id == ids[0] + n;
        }
        k += n;
        if (presentByList(behaviour) || behaviour->presence({slots, n}, {present, n})) {
            for (std::size_t j = 0; j < n; ++j) s.present[ids[j]] = 1;
        } else {  // only the present ones, packed (without a branch: who is present is random)
            std::size_t m = 0;
            for (std::size_t j = 0; j < n; ++j) {
                s.present[ids[j]] = present[j];
                ids[m] = ids[j], slots[m] = slots[j];
                m += present[j] != 0;
            }
            consecutive = consecutive && m == n;
            n = m;
        }
        if (n == 0) continue;
        if (consecutive) {
            behaviour->referencePoints({slots, n}, context, ops, {s.refLocal.data() + ids[0], n});
        } else {
            behaviour->referencePoints({slots, n}, context, ops, {out, n});
            for (std::size_t j = 0; j < n; ++j) s.refLocal[ids[j]] = out[j];
        }
    }
}

/// computeReferencePointRuns asking every behaviour which of its actors are present.
template <class IdOf>
void computeReferencePointRuns(Crowd::State& s, std::size_t begin, std::size_t end, IdOf&& idOf, const FrameContext& context,
                               OpTally* ops) {
    computeReferencePointRuns(s, begin, end, idOf, context, ops, [](const Behaviour*) { return false; });
}

}  // namespace throng::detail
