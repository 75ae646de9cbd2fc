#include "throng/sim/NavMesh.h"

#include <DetourCommon.h>
#include <DetourNavMesh.h>
#include <DetourNavMeshBuilder.h>
#include <DetourNavMeshQuery.h>
#include <Recast.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include <glm/common.hpp>

#include "throng/scenegraph/ByteStream.h"
#include "throng/scenegraph/ThreadTeam.h"
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


// Detour data for one tile.
struct TileData {
    unsigned char* data = nullptr;
    int size = 0;
    int polys = 0;
};

// Builds the Detour tile (tx, tz) of `cfg` (its bounds and size set, with its border) from the
// triangles `tris` and blocked boxes `boxes` of `g`. No data if nothing in it is walkable.
TileData buildTile(const NavGeometry& g, const std::vector<int>& tris, const std::vector<int>& boxes, const NavMeshSettings& s,
                   rcConfig cfg, int tx, int tz) {
    rcContext ctx(false);
    const float* verts = &g.vertices[0].x;
    const int nverts = static_cast<int>(g.vertices.size());
    const int ntris = static_cast<int>(tris.size());
    std::vector<int> indices(tris.size() * 3);
    for (std::size_t t = 0; t < tris.size(); ++t)
        for (int k = 0; k < 3; ++k) indices[3 * t + k] = int(g.indices[3 * std::size_t(tris[t]) + k]);
    RecastPtr<rcHeightfield> solid(rcAllocHeightfield());
    if (!solid || !rcCreateHeightfield(&ctx, *solid, cfg.width, cfg.height, cfg.bmin, cfg.bmax, cfg.cs, cfg.ch))
        fail("creating the heightfield (" + std::to_string(cfg.width) + " x " + std::to_string(cfg.height) + " cells)");
    // Walkable triangles keep Recast's slope test; obstacles never become walkable.
    std::vector<unsigned char> areas(tris.size(), 0);
    rcMarkWalkableTriangles(&ctx, cfg.walkableSlopeAngle, verts, nverts, indices.data(), ntris, areas.data());
    for (std::size_t t = 0; t < areas.size(); ++t)
        if (!g.walkable[std::size_t(tris[t])]) areas[t] = RC_NULL_AREA;
    if (!rcRasterizeTriangles(&ctx, verts, nverts, indices.data(), areas.data(), ntris, *solid, cfg.walkableClimb))
        fail("rasterizing the triangles");
    rcFilterLowHangingWalkableObstacles(&ctx, cfg.walkableClimb, *solid);
    rcFilterLedgeSpans(&ctx, cfg.walkableHeight, cfg.walkableClimb, *solid);
    rcFilterWalkableLowHeightSpans(&ctx, cfg.walkableHeight, *solid);
    RecastPtr<rcCompactHeightfield> chf(rcAllocCompactHeightfield());
    if (!chf || !rcBuildCompactHeightfield(&ctx, cfg.walkableHeight, cfg.walkableClimb, *solid, *chf)) fail("compacting the heightfield");
    solid.reset();
    // Inside blocked volumes nothing is walkable (reaching half a metre below, to the ground they stand on).
    for (int b : boxes) {
        const auto& [lo, hi] = g.blocked[std::size_t(b)];
        const glm::vec3 low(lo.x, lo.y - 0.5f, lo.z);
        rcMarkBoxArea(&ctx, &low.x, &hi.x, RC_NULL_AREA, *chf);
    }
    if (!rcErodeWalkableArea(&ctx, cfg.walkableRadius, *chf)) fail("eroding by the agent radius");
    if (!rcBuildDistanceField(&ctx, *chf)) fail("building the distance field");
    if (!rcBuildRegions(&ctx, *chf, cfg.borderSize, cfg.minRegionArea, cfg.mergeRegionArea)) fail("building regions");
    RecastPtr<rcContourSet> cset(rcAllocContourSet());
    if (!cset || !rcBuildContours(&ctx, *chf, cfg.maxSimplificationError, cfg.maxEdgeLen, *cset)) fail("building contours");
    if (cset->nconts == 0) return {};
    RecastPtr<rcPolyMesh> pmesh(rcAllocPolyMesh());
    if (!pmesh || !rcBuildPolyMesh(&ctx, *cset, cfg.maxVertsPerPoly, *pmesh)) fail("building the polygon mesh");
    RecastPtr<rcPolyMeshDetail> dmesh(rcAllocPolyMeshDetail());
    if (!dmesh || !rcBuildPolyMeshDetail(&ctx, *pmesh, *chf, cfg.detailSampleDist, cfg.detailSampleMaxError, *dmesh))
        fail("building the detail mesh");
    if (pmesh->nverts >= 0xffff) throw std::runtime_error("NavMesh::build: too many vertices for one Detour tile; use smaller tiles");
    if (pmesh->npolys == 0) return {};
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
    params.tileX = tx;
    params.tileY = tz;
    rcVcopy(params.bmin, pmesh->bmin);
    rcVcopy(params.bmax, pmesh->bmax);
    params.cs = cfg.cs;
    params.ch = cfg.ch;
    params.buildBvTree = true;
    TileData out;
    out.polys = pmesh->npolys;
    if (!dtCreateNavMeshData(&params, &out.data, &out.size)) fail("creating Detour's navigation mesh data");
    return out;
}

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
    rcCalcBounds(&g.vertices[0].x, static_cast<int>(g.vertices.size()), cfg.bmin, cfg.bmax);

    std::shared_ptr<NavMesh> nav(new NavMesh());
    nav->settings_ = s;
    nav->mesh_ = dtAllocNavMesh();
    if (!nav->mesh_) fail("allocating Detour's navigation mesh");
    if (!(s.tileSize > 0.0f)) {
        // One tile over everything.
        std::vector<int> all(g.triangleCount());
        for (std::size_t t = 0; t < all.size(); ++t) all[t] = int(t);
        std::vector<int> blocked(g.blocked.size());
        for (std::size_t b = 0; b < blocked.size(); ++b) blocked[b] = int(b);
        rcCalcGridSize(cfg.bmin, cfg.bmax, cfg.cs, &cfg.width, &cfg.height);
        const TileData tile = buildTile(g, all, blocked, s, cfg, 0, 0);
        if (!tile.data) throw std::runtime_error("NavMesh::build: the geometry has no walkable area");
        if (dtStatusFailed(nav->mesh_->init(tile.data, tile.size, DT_TILE_FREE_DATA))) {
            dtFree(tile.data);
            fail("initialising Detour's navigation mesh");
        }
    } else {
        // Square tiles, each rasterised with a border of cells around it so that neighbours join.
        const int tileCells = std::max(16, static_cast<int>(s.tileSize / cfg.cs));
        const float tileMetres = float(tileCells) * cfg.cs;
        const int border = cfg.walkableRadius + 3;
        const float borderMetres = float(border) * cfg.cs;
        const int tilesX = std::max(1, int(std::ceil((cfg.bmax[0] - cfg.bmin[0]) / tileMetres)));
        const int tilesZ = std::max(1, int(std::ceil((cfg.bmax[2] - cfg.bmin[2]) / tileMetres)));
        const std::size_t tileCount = std::size_t(tilesX) * std::size_t(tilesZ);
        // Detour's 32-bit polygon references share 22 bits between the tile and the polygon.
        int tileBits = 0;
        while ((std::size_t(1) << tileBits) < tileCount) ++tileBits;
        if (tileBits > 14)
            throw std::runtime_error("NavMesh::build: " + std::to_string(tilesX) + " x " + std::to_string(tilesZ) +
                                     " tiles are more than Detour's polygon references can number (16384); use larger tiles");
        const int maxPolys = 1 << (22 - tileBits);
        dtNavMeshParams params{};
        rcVcopy(params.orig, cfg.bmin);
        params.tileWidth = params.tileHeight = tileMetres;
        params.maxTiles = int(tileCount);
        params.maxPolys = maxPolys;
        if (dtStatusFailed(nav->mesh_->init(&params))) fail("initialising Detour's tiled navigation mesh");
        // Which triangles and blocked boxes reach each tile (with its border).
        std::vector<std::vector<int>> tris(tileCount), boxes(tileCount);
        auto span = [&](float lo, float hi, float origin, int count, int& first, int& last) {
            first = std::clamp(int(std::floor((lo - borderMetres - origin) / tileMetres)), 0, count - 1);
            last = std::clamp(int(std::floor((hi + borderMetres - origin) / tileMetres)), 0, count - 1);
        };
        auto bin = [&](glm::vec3 lo, glm::vec3 hi, std::vector<std::vector<int>>& lists, int item) {
            int x0, x1, z0, z1;
            span(lo.x, hi.x, cfg.bmin[0], tilesX, x0, x1);
            span(lo.z, hi.z, cfg.bmin[2], tilesZ, z0, z1);
            for (int z = z0; z <= z1; ++z)
                for (int x = x0; x <= x1; ++x) lists[std::size_t(z) * tilesX + x].push_back(item);
        };
        for (std::size_t t = 0; t < g.triangleCount(); ++t) {
            const glm::vec3 &a = g.vertices[g.indices[3 * t]], &b = g.vertices[g.indices[3 * t + 1]], &c = g.vertices[g.indices[3 * t + 2]];
            bin(glm::min(a, glm::min(b, c)), glm::max(a, glm::max(b, c)), tris, int(t));
        }
        for (std::size_t k = 0; k < g.blocked.size(); ++k) bin(g.blocked[k].first, g.blocked[k].second, boxes, int(k));
        std::vector<TileData> built(tileCount);
        forEachChunk(tileCount, 1, [&](std::size_t, std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) {
                if (tris[i].empty()) continue;
                const int tx = int(i % std::size_t(tilesX)), tz = int(i / std::size_t(tilesX));
                rcConfig tc = cfg;
                tc.borderSize = border;
                tc.width = tc.height = tileCells + 2 * border;
                tc.bmin[0] = cfg.bmin[0] + float(tx) * tileMetres - borderMetres;
                tc.bmin[2] = cfg.bmin[2] + float(tz) * tileMetres - borderMetres;
                tc.bmax[0] = cfg.bmin[0] + float(tx + 1) * tileMetres + borderMetres;
                tc.bmax[2] = cfg.bmin[2] + float(tz + 1) * tileMetres + borderMetres;
                built[i] = buildTile(g, tris[i], boxes[i], s, tc, tx, tz);
                if (built[i].data && built[i].polys > maxPolys) {
                    dtFree(built[i].data);
                    built[i].data = nullptr;
                    throw std::runtime_error("NavMesh::build: a tile holds " + std::to_string(built[i].polys) + " polygons, more than " +
                                             std::to_string(maxPolys) + "; use smaller tiles");
                }
            }
        });
        // Added in tile order, whatever thread built them.
        bool any = false;
        for (TileData& t : built) {
            if (!t.data) continue;
            any = true;
            if (dtStatusFailed(nav->mesh_->addTile(t.data, t.size, DT_TILE_FREE_DATA, 0, nullptr))) {
                dtFree(t.data);
                for (TileData& rest : built)
                    if (rest.data && &rest > &t) dtFree(rest.data);
                fail("adding a tile to Detour's navigation mesh");
            }
        }
        if (!any) throw std::runtime_error("NavMesh::build: the geometry has no walkable area");
    }
    nav->query_ = dtAllocNavMeshQuery();
    if (!nav->query_ || dtStatusFailed(nav->query_->init(nav->mesh_, 4096))) fail("initialising the navigation query");
    nav->indexPolygons();
    return nav;
}

namespace {

constexpr char kBytesMagic[4] = {'T', 'N', 'A', 'V'};
constexpr std::uint32_t kBytesVersion = 1;

}  // namespace

std::vector<std::byte> NavMesh::toBytes() const {
    std::vector<std::byte> bytes;
    ByteWriter out(bytes);
    out.putBytes(kBytesMagic, sizeof kBytesMagic);
    out.put(kBytesVersion);
    out.put(settings_);
    out.put(*mesh_->getParams());
    const dtNavMesh* m = mesh_;
    std::uint32_t tiles = 0;
    for (int t = 0; t < m->getMaxTiles(); ++t)
        if (const dtMeshTile* tile = m->getTile(t); tile && tile->header) ++tiles;
    out.put(tiles);
    for (int t = 0; t < m->getMaxTiles(); ++t) {
        const dtMeshTile* tile = m->getTile(t);
        if (!tile || !tile->header) continue;
        out.put(std::uint64_t(m->getTileRef(tile)));
        out.put(std::uint32_t(tile->dataSize));
        out.putBytes(tile->data, std::size_t(tile->dataSize));
    }
    return bytes;
}

std::shared_ptr<NavMesh> NavMesh::fromBytes(std::span<const std::byte> bytes) {
    ByteReader in(bytes, "NavMesh::fromBytes");
    char magic[4];
    in.read(magic, 4, "the header");
    if (!std::equal(magic, magic + 4, kBytesMagic)) throw std::invalid_argument("NavMesh::fromBytes: not a navigation mesh's bytes");
    if (const auto version = in.get<std::uint32_t>("the header"); version != kBytesVersion)
        throw std::invalid_argument("NavMesh::fromBytes: version " + std::to_string(version) + ", this build reads version " +
                                    std::to_string(kBytesVersion));
    std::shared_ptr<NavMesh> nav(new NavMesh());
    nav->settings_ = in.get<NavMeshSettings>("the settings");
    const dtNavMeshParams params = in.get<dtNavMeshParams>("Detour's parameters");
    const auto tiles = in.get<std::uint32_t>("the tile count");
    if (tiles == 0 || tiles > std::uint32_t(std::max(params.maxTiles, 1)))
        throw std::invalid_argument("NavMesh::fromBytes: " + std::to_string(tiles) + " tiles for a mesh of at most " +
                                    std::to_string(params.maxTiles));
    nav->mesh_ = dtAllocNavMesh();
    if (!nav->mesh_) throw std::runtime_error("NavMesh::fromBytes: Detour could not allocate a navigation mesh");
    if (dtStatusFailed(nav->mesh_->init(&params))) throw std::invalid_argument("NavMesh::fromBytes: Detour refuses the mesh's parameters");
    for (std::uint32_t k = 0; k < tiles; ++k) {
        const std::string what = "tile " + std::to_string(k) + " of " + std::to_string(tiles);
        const auto ref = in.get<std::uint64_t>(what);
        const auto size = in.get<std::uint32_t>(what);
        if (size < sizeof(dtMeshHeader) || size > std::uint32_t(INT_MAX))
            throw std::invalid_argument("NavMesh::fromBytes: " + what + " holds " + std::to_string(size) + " bytes, not a Detour tile");
        auto* data = static_cast<unsigned char*>(dtAlloc(size, DT_ALLOC_PERM));
        if (!data) throw std::runtime_error("NavMesh::fromBytes: out of memory for " + what);
        try {
            in.read(data, size, what);
        } catch (...) {
            dtFree(data);
            throw;
        }
        // The same slot and salt as in the original: every polygon keeps its reference.
        if (dtStatusFailed(nav->mesh_->addTile(data, int(size), DT_TILE_FREE_DATA, dtTileRef(ref), nullptr))) {
            dtFree(data);
            throw std::invalid_argument("NavMesh::fromBytes: Detour refuses " + what + " (not tile data of this Detour, or its place is taken)");
        }
    }
    if (in.remaining() != 0)
        throw std::invalid_argument("NavMesh::fromBytes: " + std::to_string(in.remaining()) + " bytes follow the last tile");
    nav->query_ = dtAllocNavMeshQuery();
    if (!nav->query_ || dtStatusFailed(nav->query_->init(nav->mesh_, 4096)))
        throw std::runtime_error("NavMesh::fromBytes: Detour could not initialise a navigation query");
    nav->indexPolygons();
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
    if (polyAreaSum_.empty() || !(polyAreaSum_.back() > 0.0)) throw std::runtime_error("NavMesh::randomPoint: the mesh has no walkable polygon");
    const std::uint64_t c = counter * 4;  // three numbers per point
    const double pick = rng.uniform(c) * polyAreaSum_.back();
    const std::size_t i = std::min<std::size_t>(std::size_t(std::upper_bound(polyAreaSum_.begin(), polyAreaSum_.end(), pick) - polyAreaSum_.begin()),
                                                polyAreaSum_.size() - 1);
    const dtPolyRef ref = dtPolyRef(polyRefs_[i]);
    const dtMeshTile* tile = nullptr;
    const dtPoly* poly = nullptr;
    mesh_->getTileAndPolyByRefUnsafe(ref, &tile, &poly);
    float verts[3 * DT_VERTS_PER_POLYGON], areas[DT_VERTS_PER_POLYGON];
    for (int v = 0; v < poly->vertCount; ++v) dtVcopy(&verts[v * 3], &tile->verts[poly->verts[v] * 3]);
    glm::vec3 out(0.0f);
    dtRandomPointInConvexPoly(verts, poly->vertCount, areas, float(rng.uniform(c + 1)), float(rng.uniform(c + 2)), &out.x);
    float h = out.y;
    if (dtStatusSucceed(query.getPolyHeight(ref, &out.x, &h))) out.y = h;
    return out;
}

void NavMesh::indexPolygons() {
    const dtNavMesh* m = mesh_;
    double sum = 0.0;
    bool boundsSet = false;
    for (int t = 0; t < m->getMaxTiles(); ++t) {
        const dtMeshTile* tile = m->getTile(t);
        if (!tile || !tile->header) continue;
        const dtPolyRef base = m->getPolyRefBase(tile);
        auto widen = [&](const float* v, int count) {
            for (int k = 0; k < count; ++k) {
                const glm::vec3 p(v[3 * k], v[3 * k + 1], v[3 * k + 2]);
                if (!boundsSet) lo_ = hi_ = p, boundsSet = true;
                lo_ = glm::min(lo_, p), hi_ = glm::max(hi_, p);
            }
        };
        widen(tile->verts, tile->header->vertCount);
        widen(tile->detailVerts, tile->header->detailVertCount);
        for (int p = 0; p < tile->header->polyCount; ++p) {
            const dtPoly& poly = tile->polys[p];
            if (poly.getType() != DT_POLYTYPE_GROUND || !(poly.flags & kWalkFlag)) continue;
            double area = 0.0;
            for (int v = 2; v < poly.vertCount; ++v)
                area += dtTriArea2D(&tile->verts[poly.verts[0] * 3], &tile->verts[poly.verts[v - 1] * 3], &tile->verts[poly.verts[v] * 3]);
            sum += std::abs(area);
            polyRefs_.push_back(base | dtPolyRef(p));
            polyAreaSum_.push_back(sum);
        }
    }
}

int NavMesh::polygonCount() const {
    const dtNavMesh* m = mesh_;
    int n = 0;
    for (int i = 0; i < m->getMaxTiles(); ++i)
        if (const dtMeshTile* tile = m->getTile(i); tile && tile->header) n += tile->header->polyCount;
    return n;
}

}  // namespace throng::sim
