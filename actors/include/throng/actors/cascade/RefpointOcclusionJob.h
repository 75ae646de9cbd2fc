#pragma once
// Phase 2 of actor processing, occlusion: the Refpoint Bspheres that passed CULL 1 against the
// frame's occlusion buffer, before any Skeleton Root, behaviour or pose is computed for them.
// Nearby actors are binned into cells on the ground plane and each cell is tested as one sphere
// first: a street hidden behind a block costs one test, not one per actor. Cells are fixed in the
// world and split by the region stepping their actors, so that how many tests a frame takes does
// not depend on how the actors are split over processes.

#include <span>
#include <vector>

#include "throng/actors/Crowd.h"
#include "throng/actors/cascade/CascadeTypes.h"
#include "throng/actors/cascade/PhaseLoop.h"

namespace throng {
class OcclusionBuffer;
}

namespace throng::cascade {

/// Removes the survivors of CULL 1 that the occlusion buffer hides.
struct RefpointOcclusionJob {
    /// A cell of nearby survivors: a square of the ground grid (fixed in the world) within one
    /// region of the behaviour stepping them (Behaviour::steppingRegions; 0: none).
    struct Cell {
        std::int32_t x = 0;                      ///< the square along x, in squares from the world's origin
        std::int32_t z = 0;                      ///< the square along z
        std::uint32_t region = 0;                ///< 1 + the region, 0 for actors of no region
        /// Same square, same region.
        friend bool operator==(const Cell&, const Cell&) = default;
    };
    /// The cells of nearby survivors, kept between frames.
    struct Scratch {
        std::vector<Cell> cell;                  ///< per survivor: its cell
        std::vector<std::uint32_t> cellOf;       ///< per survivor: its cell's bucket (a square of the window, or a hash)
        std::vector<std::uint32_t> cellStart;    ///< per bucket: first entry in cellMembers (one more at the end)
        std::vector<std::uint32_t> cellMembers;  ///< survivor positions, bucket by bucket, cell by cell
        std::vector<std::uint32_t> cellCursor;   ///< per bucket: where its next member goes
        std::vector<std::uint8_t> hidden;        ///< per survivor: rejected by occlusion
    };

    /// In: refSphereWorld.
    const Crowd::State* crowd = nullptr;
    /// In: this frame's occluders, or null: the job does nothing.
    const OcclusionBuffer* occlusion = nullptr;
    /// In: the candidates.
    std::span<const Candidate> candidates;
    /// In and out: the survivors of CULL 1; the hidden leave, the order of the others is kept.
    std::vector<std::uint32_t>* survivors = nullptr;
    /// Out, per actor of the crowd: ActorClass::Occluded for the hidden. Counts occludedRefpoint,
    /// occlusionCellsTested, occlusionCellsHidden and occlusionTests.
    std::span<ActorClass> actorClass;
    /// The job's workspace.
    Scratch* scratch = nullptr;

    /// Null when the job can run, else what is wrong.
    const char* problem() const;
    /// True when the job can run.
    bool validate() const { return problem() == nullptr; }
    /// Runs the job; throws std::invalid_argument naming the problem when it cannot run.
    void run(PhaseLoop& loop) const;
};

}  // namespace throng::cascade
