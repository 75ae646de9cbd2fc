#pragma once
// Phase 1 of actor processing: the Reference Point of every actor, in the scene or not, whatever
// the camera (it is simulation state). Each behaviour is asked for runs of its actors at once.

#include <vector>

#include "throng/actors/Crowd.h"
#include "throng/actors/cascade/PhaseLoop.h"
#include "throng/scenegraph/FrameContext.h"

namespace throng::cascade {

/// Computes every actor's local Reference Point and resets its frame classification.
struct ReferencePointsJob {
    /// In and out: reads every actor's behaviour and slot; writes present, refLocal (of the present
    /// only), eyeDistance (infinite until CULL 2 computes it) and actorClass (CulledWithGroup, A for
    /// an absent actor, or NotInScene); marks the nodes' bounds dirty. Counts actorsInScene, and
    /// the absent in the scene in both actorsAbsent and a.
    Crowd* crowd = nullptr;
    /// In: the frame's time and number (its counter is the loop's).
    FrameContext context;

    /// The actors a crowd visits when a behaviour lists its present slots (Behaviour::presentSlots),
    /// kept between frames.
    struct Listed {
        std::vector<ActorId> visit;  ///< this frame: the listed actors, then those of behaviours listing none
        std::vector<ActorId> shown;  ///< present after phase 1 (last frame's until the job runs)
        std::vector<const Behaviour*> listing;  ///< this frame: the behaviours that list their present slots
        bool active = false;         ///< the last frame was visited so (every other actor's present is 0)
    };
    /// In and out, optional: when given and a behaviour lists its present slots, only the actors in
    /// `listed->visit` and those shown last frame are visited (a listed actor is present without
    /// asking its behaviour): the others stay absent (present 0, class A or NotInScene), unread.
    /// Otherwise, or when null, every actor is.
    Listed* listed = nullptr;

    /// Null when the job can run, else what is wrong.
    const char* problem() const;
    /// True when the job can run.
    bool validate() const { return problem() == nullptr; }
    /// Runs the job; throws std::invalid_argument naming the problem when it cannot run.
    void run(PhaseLoop& loop) const;

private:
    void runListed(PhaseLoop& loop) const;  // the visit of the listed actors only
};

}  // namespace throng::cascade
