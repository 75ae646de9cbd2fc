// Phase 2 of actor processing, occlusion (see RefpointOcclusionJob.h).

#include <algorithm>
#include <cmath>

#include "throng/actors/cascade/RefpointOcclusionJob.h"
#include "throng/scenegraph/OcclusionBuffer.h"

namespace throng::cascade {
namespace {

constexpr double kCellSize = 12.0;       // metres: about a street's width
constexpr std::uint32_t kMaxCellsPerSide = 64;
constexpr std::size_t kCellGrain = 16;    // cells per chunk of the parallel loop

}  // namespace

const char* RefpointOcclusionJob::problem() const {
    if (!crowd || !survivors || !scratch) return "crowd, survivors and scratch are required";
    if (actorClass.size() != crowd->tmpl.size()) return "actorClass must have one entry per actor";
    if (survivors->size() > candidates.size()) return "more survivors than candidates";
    return nullptr;
}

void RefpointOcclusionJob::run(PhaseLoop& loop) const {
    throwIfInvalid("RefpointOcclusionJob", loop.ready() ? problem() : "the loop has no frame");
    std::vector<std::uint32_t>& alive = *survivors;
    const std::size_t n = alive.size();
    if (!occlusion || n == 0) return;
    const Crowd::State& s = *crowd;
    const OcclusionBuffer& buffer = *occlusion;
    Scratch& w = *scratch;
    const auto sphereOf = [&](std::size_t k) -> const BoundingSphere& { return s.refSphereWorld[candidates[alive[k]].id]; };

    // Bin the survivors into cells by their Refpoint on the ground plane (counting sort: stable, so
    // the order inside a cell is the survivors' order).
    double minX = sphereOf(0).center().x, maxX = minX;
    double minZ = sphereOf(0).center().z, maxZ = minZ;
    for (std::size_t k = 1; k < n; ++k) {
        const Vec3& c = sphereOf(k).center();
        minX = std::min(minX, c.x), maxX = std::max(maxX, c.x);
        minZ = std::min(minZ, c.z), maxZ = std::max(maxZ, c.z);
    }
    const double cell = std::max({kCellSize, (maxX - minX) / kMaxCellsPerSide, (maxZ - minZ) / kMaxCellsPerSide});
    const auto cellsAlong = [&](double extent) { return std::min<std::uint32_t>(kMaxCellsPerSide, static_cast<std::uint32_t>(extent / cell) + 1); };
    const std::uint32_t cx = cellsAlong(maxX - minX), cz = cellsAlong(maxZ - minZ), cells = cx * cz;
    w.cellOf.resize(n);
    w.cellStart.assign(cells + 1, 0);
    for (std::size_t k = 0; k < n; ++k) {
        const Vec3& c = sphereOf(k).center();
        const auto ix = std::min(cx - 1, static_cast<std::uint32_t>((c.x - minX) / cell));
        const auto iz = std::min(cz - 1, static_cast<std::uint32_t>((c.z - minZ) / cell));
        w.cellOf[k] = iz * cx + ix;
        ++w.cellStart[w.cellOf[k] + 1];
    }
    for (std::uint32_t c = 0; c < cells; ++c) w.cellStart[c + 1] += w.cellStart[c];
    w.cellMembers.resize(n);
    w.cellCursor.assign(w.cellStart.begin(), w.cellStart.end() - 1);
    for (std::size_t k = 0; k < n; ++k) w.cellMembers[w.cellCursor[w.cellOf[k]]++] = static_cast<std::uint32_t>(k);

    w.hidden.assign(n, 0);
    loop.parallel(cells, kCellGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        for (std::size_t c = begin; c < end; ++c) {
            const std::uint32_t first = w.cellStart[c], last = w.cellStart[c + 1];
            if (first == last) continue;
            if (last - first > 1) {
                // The cell's sphere: around the box of its actors' spheres.
                Vec3 lo(1e300), hi(-1e300);
                for (std::uint32_t m = first; m < last; ++m) {
                    const BoundingSphere& b = sphereOf(w.cellMembers[m]);
                    lo = glm::min(lo, b.center() - Vec3(b.radius()));
                    hi = glm::max(hi, b.center() + Vec3(b.radius()));
                }
                ++out.counts.occlusionCellsTested;
                ++out.counts.occlusionTests;
                if (buffer.occluded(BoundingSphere(0.5 * (lo + hi), 0.5 * glm::length(hi - lo)))) {
                    ++out.counts.occlusionCellsHidden;
                    for (std::uint32_t m = first; m < last; ++m) w.hidden[w.cellMembers[m]] = 1;
                    continue;
                }
            }
            for (std::uint32_t m = first; m < last; ++m) {
                const std::uint32_t k = w.cellMembers[m];
                ++out.counts.occlusionTests;
                w.hidden[k] = buffer.occluded(sphereOf(k)) ? 1 : 0;
            }
        }
    });

    // Every survivor was tested, with its cell or alone.
    loop.statistics().occlusionObjectsTested += n;
    // The hidden leave the survivors, whose order is kept.
    std::size_t kept = 0;
    for (std::size_t k = 0; k < n; ++k) {
        const std::uint32_t candidate = alive[k];
        if (w.hidden[k]) {
            actorClass[candidates[candidate].id] = ActorClass::Occluded;
            ++loop.statistics().occludedRefpoint;
        } else {
            alive[kept++] = candidate;
        }
    }
    alive.resize(kept);
}

}  // namespace throng::cascade
