// Phase 2 of actor processing, occlusion: the Refpoint Bspheres that passed CULL 1 against the
// frame's occlusion buffer, before any Skeleton Root, behaviour or pose is computed for them.
// Nearby actors are binned into cells on the ground plane and each cell is tested as one sphere
// first: a street hidden behind a block costs one test, not one per actor.

#include <algorithm>
#include <cmath>

#include "CascadeFrame.h"
#include "throng/actors/Crowd.h"
#include "throng/scenegraph/OcclusionBuffer.h"

namespace throng::cascade {
namespace {

constexpr double kCellSize = 12.0;       // metres: about a street's width
constexpr std::uint32_t kMaxCellsPerSide = 64;
constexpr std::size_t kCellGrain = 16;    // cells per chunk of the parallel loop

}  // namespace

void occludeReferencePoints(CascadeFrame& f) {
    const std::size_t n = f.survivors.size();
    if (!f.occlusion || n == 0) return;
    Crowd::State& s = f.crowd->state();
    const OcclusionBuffer& buffer = *f.occlusion;

    // Bin the survivors into cells by their Refpoint on the ground plane (counting sort: stable, so
    // the order inside a cell is the survivors' order).
    double minX = s.refSphereWorld[f.candidates[f.survivors[0]].id].center().x, maxX = minX;
    double minZ = s.refSphereWorld[f.candidates[f.survivors[0]].id].center().z, maxZ = minZ;
    for (std::size_t k = 1; k < n; ++k) {
        const Vec3& c = s.refSphereWorld[f.candidates[f.survivors[k]].id].center();
        minX = std::min(minX, c.x), maxX = std::max(maxX, c.x);
        minZ = std::min(minZ, c.z), maxZ = std::max(maxZ, c.z);
    }
    const double cell = std::max({kCellSize, (maxX - minX) / kMaxCellsPerSide, (maxZ - minZ) / kMaxCellsPerSide});
    const auto cellsAlong = [&](double extent) { return std::min<std::uint32_t>(kMaxCellsPerSide, static_cast<std::uint32_t>(extent / cell) + 1); };
    const std::uint32_t cx = cellsAlong(maxX - minX), cz = cellsAlong(maxZ - minZ), cells = cx * cz;
    f.cellOf.resize(n);
    f.cellStart.assign(cells + 1, 0);
    for (std::size_t k = 0; k < n; ++k) {
        const Vec3& c = s.refSphereWorld[f.candidates[f.survivors[k]].id].center();
        const auto ix = std::min(cx - 1, static_cast<std::uint32_t>((c.x - minX) / cell));
        const auto iz = std::min(cz - 1, static_cast<std::uint32_t>((c.z - minZ) / cell));
        f.cellOf[k] = iz * cx + ix;
        ++f.cellStart[f.cellOf[k] + 1];
    }
    for (std::uint32_t c = 0; c < cells; ++c) f.cellStart[c + 1] += f.cellStart[c];
    f.cellMembers.resize(n);
    f.cellCursor.assign(f.cellStart.begin(), f.cellStart.end() - 1);
    for (std::size_t k = 0; k < n; ++k) f.cellMembers[f.cellCursor[f.cellOf[k]]++] = static_cast<std::uint32_t>(k);

    f.hidden.assign(n, 0);
    f.parallel(cells, kCellGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        for (std::size_t c = begin; c < end; ++c) {
            const std::uint32_t first = f.cellStart[c], last = f.cellStart[c + 1];
            if (first == last) continue;
            if (last - first > 1) {
                // The cell's sphere: around the box of its actors' spheres.
                Vec3 lo(1e300), hi(-1e300);
                for (std::uint32_t m = first; m < last; ++m) {
                    const BoundingSphere& b = s.refSphereWorld[f.candidates[f.survivors[f.cellMembers[m]]].id];
                    lo = glm::min(lo, b.center() - Vec3(b.radius()));
                    hi = glm::max(hi, b.center() + Vec3(b.radius()));
                }
                ++out.counts.occlusionCellsTested;
                ++out.counts.occlusionTests;
                if (buffer.occluded(BoundingSphere(0.5 * (lo + hi), 0.5 * glm::length(hi - lo)))) {
                    ++out.counts.occlusionCellsHidden;
                    for (std::uint32_t m = first; m < last; ++m) f.hidden[f.cellMembers[m]] = 1;
                    continue;
                }
            }
            for (std::uint32_t m = first; m < last; ++m) {
                const std::uint32_t k = f.cellMembers[m];
                ++out.counts.occlusionTests;
                f.hidden[k] = buffer.occluded(s.refSphereWorld[f.candidates[f.survivors[k]].id]) ? 1 : 0;
            }
        }
    });

    // The hidden leave the survivors, whose order is kept.
    std::size_t kept = 0;
    for (std::size_t k = 0; k < n; ++k) {
        const std::uint32_t candidate = f.survivors[k];
        if (f.hidden[k]) {
            s.actorClass[f.candidates[candidate].id] = ActorClass::Occluded;
            ++f.stats->occludedRefpoint;
        } else {
            f.survivors[kept++] = candidate;
        }
    }
    f.survivors.resize(kept);
}

}  // namespace throng::cascade
