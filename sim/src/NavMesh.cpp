#include "throng/sim/NavMesh.h"

#include <DetourNavMesh.h>
#include <DetourNavMeshBuilder.h>
#include <DetourNavMeshQuery.h>
#include <Recast.h>

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "throng/sim/CounterRng.h"

namespace throng::sim {
namespace {

// Recast objects freed on scope exit.
struct RecastDeleter {
    void operator()(rcHeightfield* p) const { rcFreeHeightField(p); }
    void operator()(rcCompactHeightfield* p) const { rcFreeCompactHeightfield(p); }
    void operator()(rcContourSet* p) const { rcFreeContourSet(p); }
    void operator()(rcPolyMesh* p) const { rcFreePolyMesh(p); }
    void operator()(rcPolyMeshDetail* p) const { rcFreePolyMeshDetail(p); }
};
template <class T>
using RecastPtr = std::unique_ptr<T, RecastDeleter>;

[[noreturn]] void fail(const std::string& step) { throw std::runtime_error("NavMesh::build: Recast/Detour step failed: " + step); }

constexpr unsigned short kWalkFlag = 1;

// Detour's random point query takes a plain function: the stream for the current call.
thread_local const CounterRng* tRng = nullptr;
thread_local std::uint64_t tCounter = 0;
float nextRandom() { return static_cast<float>(tRng->uniform(tCounter++)); }

}  // namespace

std::shared_ptr<NavMesh> NavMesh::build(const NavGeometry& g, const NavMeshSettings& s) {
    if (g.triangleCount() == 0) throw std::invalid_argument("NavMesh::build: the geometry has no triangles");
    if (g.walkable.size() != g.triangleCount())
        throw std::invalid_argument("NavMesh::build: " + std::to_string(g.walkable.size()) + " walkable flags for " +
                                    std::to_string(g.triangleCount()) + " triangles");
    for (const glm::vec3& v : g.vertices)
        if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
            throw std::invalid_argument("NavMesh::build: a vertex is not finite");
    for (std::uint32_t i : g.indices)
        if (i >= g.vertices.size()) throw std::invalid_argument("NavMesh::build: an index is out of range");

    rcContext ctx(false);
    rcConfig cfg{};
    cfg.cs = s.cellSize;
    cfg.ch = s.cellHeight;
    cfg.walkableSlopeAngle = s.agentMaxSlope;
    cfg.walkableHeight = static_cast<int>(std::ceil(s.agentHeight / cfg.ch));
    cfg.walkableClimb = static_cast<int>(std::floor(s.agentMaxClimb / cfg.ch));
    cfg.walkableRadius = static_cast<int>(std::ceil(s.agentRadius / cfg.cs));
    cfg.maxEdgeLen = static_cast<int>(s.edgeMaxLength / cfg.cs);
    cfg.maxSimplificationError = s.edgeMaxError;
    cfg.minRegionArea = static_cast<int>(s.regionMinSize * s.regionMinSize);
    cfg.mergeRegionArea = static_cast<int>(s.regionMergeSize * s.regionMergeSize);
    cfg.maxVertsPerPoly = 6;
    cfg.detailSampleDist = s.detailSampleDistance < 0.9f ? 0 : cfg.cs * s.detailSampleDistance;
    cfg.detailSampleMaxError = cfg.ch * s.detailSampleMaxError;
    const float* verts = &g.vertices[0].x;
    const int nverts = static_cast<int>(g.vertices.size());
    const int ntris = static_cast<int>(g.triangleCount());
    rcCalcBounds(verts, nverts, cfg.bmin, cfg.bmax);
    rcCalcGridSize(cfg.bmin, cfg.bmax, cfg.cs, &cfg.width, &cfg.height);

    RecastPtr<rcHeightfield> solid(rcAllocHeightfield());
    if (!solid || !rcCreateHeightfield(&ctx, *solid, cfg.width, cfg.height, cfg.bmin, cfg.bmax, cfg.cs, cfg.ch))
        fail("creating the heightfield (" + std::to_string(cfg.width) + " x " + std::to_string(cfg.height) + " cells)");
    // Walkable triangles keep Recast's slope test; obstacles never become walkable.
    std::vector<unsigned char> areas(g.triangleCount(), 0);
    const auto* tris = reinterpret_cast<const int*>(g.indices.data());
    rcMarkWalkableTriangles(&ctx, cfg.walkableSlopeAngle, verts, nverts, tris, ntris, areas.data());
    for (std::size_t t = 0; t < areas.size(); ++t)
        if (!g.walkable[t]) areas[t] = RC_NULL_AREA;
    if (!rcRasterizeTriangles(&ctx, verts, nverts, tris, areas.data(), ntris, *solid, cfg.walkableClimb))
        fail("rasterizing the triangles");
    rcFilterLowHangingWalkableObstacles(&ctx, cfg.walkableClimb, *solid);
    rcFilterLedgeSpans(&ctx, cfg.walkableHeight, cfg.walkableClimb, *solid);
    rcFilterWalkableLowHeightSpans(&ctx, cfg.walkableHeight, *solid);
    RecastPtr<rcCompactHeightfield> chf(rcAllocCompactHeightfield());
    if (!chf || !rcBuildCompactHeightfield(&ctx, cfg.walkableHeight, cfg.walkableClimb, *solid, *chf)) fail("compacting the heightfield");
    solid.reset();
    // Inside blocked volumes nothing is walkable (reaching half a metre below, to the ground they stand on).
    for (const auto& [lo, hi] : g.blocked) {
        const glm::vec3 low(lo.x, lo.y - 0.5f, lo.z);
        rcMarkBoxArea(&ctx, &low.x, &hi.x, RC_NULL_AREA, *chf);
    }
    if (!rcErodeWalkableArea(&ctx, cfg.walkableRadius, *chf)) fail("eroding by the agent radius");
    if (!rcBuildDistanceField(&ctx, *chf)) fail("building the distance field");
    if (!rcBuildRegions(&ctx, *chf, 0, cfg.minRegionArea, cfg.mergeRegionArea)) fail("building regions");
    RecastPtr<rcContourSet> cset(rcAllocContourSet());
    if (!cset || !rcBuildContours(&ctx, *chf, cfg.maxSimplificationError, cfg.maxEdgeLen, *cset)) fail("building contours");
    if (cset->nconts == 0) throw std::runtime_error("NavMesh::build: the geometry has no walkable area");
    RecastPtr<rcPolyMesh> pmesh(rcAllocPolyMesh());
    if (!pmesh || !rcBuildPolyMesh(&ctx, *cset, cfg.maxVertsPerPoly, *pmesh)) fail("building the polygon mesh");
    RecastPtr<rcPolyMeshDetail> dmesh(rcAllocPolyMeshDetail());
    if (!dmesh || !rcBuildPolyMeshDetail(&ctx, *pmesh, *chf, cfg.detailSampleDist, cfg.detailSampleMaxError, *dmesh))
        fail("building the detail mesh");
    if (pmesh->nverts >= 0xffff) throw std::runtime_error("NavMesh::build: too many vertices for one Detour tile; use a larger cell size");
    for (int i = 0; i < pmesh->npolys; ++i)
        pmesh->flags[i] = pmesh->areas[i] == RC_WALKABLE_AREA ? kWalkFlag : 0;

    dtNavMeshCreateParams params{};
    params.verts = pmesh->verts;
    params.vertCount = pmesh->nverts;
    params.polys = pmesh->polys;
    params.polyAreas = pmesh->areas;
    params.polyFlags = pmesh->flags;
    params.polyCount = pmesh->npolys;
    params.nvp = pmesh->nvp;
    params.detailMeshes = dmesh->meshes;
    params.detailVerts = dmesh->verts;
    params.detailVertsCount = dmesh->nverts;
    params.detailTris = dmesh->tris;
    params.detailTriCount = dmesh->ntris;
    params.walkableHeight = s.agentHeight;
    params.walkableRadius = s.agentRadius;
    params.walkableClimb = s.agentMaxClimb;
    rcVcopy(params.bmin, pmesh->bmin);
    rcVcopy(params.bmax, pmesh->bmax);
    params.cs = cfg.cs;
    params.ch = cfg.ch;
    params.buildBvTree = true;
    unsigned char* data = nullptr;
    int dataSize = 0;
    if (!dtCreateNavMeshData(&params, &data, &dataSize)) fail("creating Detour's navigation mesh data");

    std::shared_ptr<NavMesh> nav(new NavMesh());
    nav->settings_ = s;
    nav->mesh_ = dtAllocNavMesh();
    if (!nav->mesh_ || dtStatusFailed(nav->mesh_->init(data, dataSize, DT_TILE_FREE_DATA))) {
        dtFree(data);
        fail("initialising Detour's navigation mesh");
    }
    nav->query_ = dtAllocNavMeshQuery();
    if (!nav->query_ || dtStatusFailed(nav->query_->init(nav->mesh_, 4096))) fail("initialising the navigation query");
    return nav;
}

NavMesh::~NavMesh() {
    dtFreeNavMeshQuery(query_);
    dtFreeNavMesh(mesh_);
}

std::optional<glm::vec3> NavMesh::nearestPoint(const glm::vec3& p, const glm::vec3& halfExtents) const {
    dtQueryFilter filter;
    dtPolyRef ref = 0;
    glm::vec3 out;
    if (dtStatusFailed(query_->findNearestPoly(&p.x, &halfExtents.x, &filter, &ref, &out.x)) || !ref) return std::nullopt;
    return out;
}

glm::vec3 NavMesh::randomPoint(const CounterRng& rng, std::uint64_t counter) const { return randomPoint(rng, counter, *query_); }

dtNavMeshQuery* NavMesh::newQuery() const {
    dtNavMeshQuery* q = dtAllocNavMeshQuery();
    if (!q || dtStatusFailed(q->init(mesh_, 4096))) {
        dtFreeNavMeshQuery(q);
        throw std::runtime_error("NavMesh::newQuery: Detour could not initialise a navigation query");
    }
    return q;
}

glm::vec3 NavMesh::randomPoint(const CounterRng& rng, std::uint64_t counter, dtNavMeshQuery& query) const {
    dtQueryFilter filter;
    dtPolyRef ref = 0;
    glm::vec3 out(0.0f);
    tRng = &rng;
    tCounter = counter * 4;  // Detour draws a few numbers per point
    const dtStatus status = query.findRandomPoint(&filter, nextRandom, &ref, &out.x);
    tRng = nullptr;
    if (dtStatusFailed(status)) throw std::runtime_error("NavMesh::randomPoint: Detour found no polygon");
    return out;
}

int NavMesh::polygonCount() const {
    const dtNavMesh* m = mesh_;
    int n = 0;
    for (int i = 0; i < m->getMaxTiles(); ++i)
        if (const dtMeshTile* tile = m->getTile(i); tile && tile->header) n += tile->header->polyCount;
    return n;
}

}  // namespace throng::sim
