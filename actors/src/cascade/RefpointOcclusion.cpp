// Phase 2 of actor processing, occlusion (see RefpointOcclusionJob.h).

#include <algorithm>
#include <cmath>
#include <tuple>

#include "throng/actors/cascade/RefpointOcclusionJob.h"
#include "throng/scenegraph/OcclusionBuffer.h"

namespace throng::cascade {
namespace {

constexpr double kCellSize = 12.0;            // metres: about a street's width
constexpr std::size_t kCellGrain = 64;         // buckets per chunk of the parallel loop
constexpr std::size_t kRegionRun = 32;         // actors per question to their behaviour
constexpr std::int64_t kMaxSquares = 1 << 16;  // a window of squares binned in order (3 km by 3 km)

// The cell holding `centre`: its square of the world's ground grid within `region`.
RefpointOcclusionJob::Cell cellOf(const Vec3& centre, std::uint32_t region) {
    const auto grid = [](double v) {  // a sphere far off (or not finite) lands at the edge, never outside int32
        return std::isfinite(v) ? static_cast<std::int32_t>(std::clamp(std::floor(v / kCellSize), -2.0e9, 2.0e9)) : 0;
    };
    return {grid(centre.x), grid(centre.z), region};
}

std::uint32_t hashOf(const RefpointOcclusionJob::Cell& c, std::uint32_t mask) {
    std::uint64_t h = std::uint64_t(std::uint32_t(c.x)) * 0x9E3779B97F4A7C15ull;
    h ^= (std::uint64_t(std::uint32_t(c.z)) + 0x632BE59BD9B4E019ull) * 0xC2B2AE3D27D4EB4Full;
    return std::uint32_t(h ^ (h >> 29)) & mask;
}

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
    const auto idOf = [&](std::size_t k) { return candidates[alive[k]].id; };
    const auto sphereOf = [&](std::size_t k) -> const BoundingSphere& { return s.refSphereWorld[idOf(k)]; };

    // Each survivor's cell: its square of the ground grid, fixed in the world (not fitted to the
    // survivors), and its region (1 + the behaviour's, 0 where it divides nothing), asked for runs
    // of actors of one behaviour. Cells never span two regions, so that processes each showing
    // some regions' actors form one process's cells between them.
    w.cell.resize(n);
    std::uint32_t slots[kRegionRun], regions[kRegionRun];
    for (std::size_t k = 0; k < n;) {
        const Behaviour* behaviour = s.behaviour[idOf(k)];
        std::size_t m = 0;
        for (; m < kRegionRun && k + m < n && s.behaviour[idOf(k + m)] == behaviour; ++m) slots[m] = s.slot[idOf(k + m)];
        const bool divided = behaviour->steppingRegions({slots, m}, {regions, m});
        for (std::size_t j = 0; j < m; ++j) w.cell[k + j] = cellOf(sphereOf(k + j).center(), divided ? regions[j] + 1 : 0);
        k += m;
    }
    // Squares into buckets (counting sort: stable): a bucket is a square of the survivors' window,
    // in order (the buffer is then read square after square), or where the window is too wide, a
    // hash of the square.
    std::int64_t x0 = w.cell[0].x, x1 = x0, z0 = w.cell[0].z, z1 = z0;
    for (const Cell& c : w.cell) {
        x0 = std::min<std::int64_t>(x0, c.x), x1 = std::max<std::int64_t>(x1, c.x);
        z0 = std::min<std::int64_t>(z0, c.z), z1 = std::max<std::int64_t>(z1, c.z);
    }
    const std::int64_t across = x1 - x0 + 1, deep = z1 - z0 + 1;
    const bool window = across <= kMaxSquares && deep <= kMaxSquares && across * deep <= kMaxSquares;
    const std::int64_t squares = window ? across * deep : 0;
    std::uint32_t buckets = 16;
    if (window) {
        buckets = std::uint32_t(squares);
    } else {
        while (buckets < n && buckets < (1u << 20)) buckets *= 2;
    }
    const auto bucketOf = [&](const Cell& c) { return window ? std::uint32_t((c.z - z0) * across + (c.x - x0)) : hashOf(c, buckets - 1); };
    w.cellOf.resize(n);
    w.cellStart.assign(buckets + 1, 0);
    for (std::size_t k = 0; k < n; ++k) ++w.cellStart[(w.cellOf[k] = bucketOf(w.cell[k])) + 1];
    for (std::uint32_t b = 0; b < buckets; ++b) w.cellStart[b + 1] += w.cellStart[b];
    w.cellMembers.resize(n);
    w.cellCursor.assign(w.cellStart.begin(), w.cellStart.end() - 1);
    for (std::size_t k = 0; k < n; ++k) w.cellMembers[w.cellCursor[w.cellOf[k]]++] = static_cast<std::uint32_t>(k);
    const auto sameCell = [&](std::uint32_t a, std::uint32_t b) { return w.cell[a] == w.cell[b]; };
    const auto cellOrder = [&](std::uint32_t a, std::uint32_t b) {  // a window's bucket is one square
        const Cell &p = w.cell[a], &q = w.cell[b];
        return window ? std::tie(p.region, a) < std::tie(q.region, b) : std::tie(p.x, p.z, p.region, a) < std::tie(q.x, q.z, q.region, b);
    };

    // A cell of two or more is tested as one sphere first (around the box of its actors' spheres):
    // hidden, so are they all; otherwise each is tested.
    w.hidden.assign(n, 0);
    const auto testCell = [&](const std::uint32_t* first, const std::uint32_t* last, ChunkOutput& out) {
        if (last - first > 1) {
            Vec3 lo(1e300), hi(-1e300);
            for (const std::uint32_t* m = first; m < last; ++m) {
                const BoundingSphere& b = sphereOf(*m);
                lo = glm::min(lo, b.center() - Vec3(b.radius()));
                hi = glm::max(hi, b.center() + Vec3(b.radius()));
            }
            ++out.counts.occlusionCellsTested;
            ++out.counts.occlusionTests;
            if (buffer.occluded(BoundingSphere(0.5 * (lo + hi), 0.5 * glm::length(hi - lo)))) {
                ++out.counts.occlusionCellsHidden;
                for (const std::uint32_t* m = first; m < last; ++m) w.hidden[*m] = 1;
                return;
            }
        }
        for (const std::uint32_t* m = first; m < last; ++m) {
            ++out.counts.occlusionTests;
            w.hidden[*m] = buffer.occluded(sphereOf(*m)) ? 1 : 0;
        }
    };
    loop.parallel(buckets, kCellGrain, [&](ChunkOutput& out, std::size_t begin, std::size_t end) {
        for (std::size_t bucket = begin; bucket < end; ++bucket) {
            std::uint32_t* const from = w.cellMembers.data() + w.cellStart[bucket];
            std::uint32_t* const to = w.cellMembers.data() + w.cellStart[bucket + 1];
            // A bucket holding more than one cell (regions in a square, squares in a hash) is
            // sorted into runs of one.
            if (std::any_of(from + 1, to, [&](std::uint32_t k) { return !sameCell(*from, k); })) std::sort(from, to, cellOrder);
            for (std::uint32_t* first = from; first < to;) {
                std::uint32_t* last = first + 1;
                while (last < to && sameCell(*first, *last)) ++last;
                testCell(first, last, out);
                first = last;
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
