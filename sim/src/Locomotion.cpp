#include "throng/sim/Locomotion.h"

#include <DetourCrowd.h>
#include <DetourNavMeshQuery.h>

#include <algorithm>
#include <cstring>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "throng/actors/ActorTemplate.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/actors/detail/SinCos.h"
#include "throng/scenegraph/Stopwatch.h"
#include "throng/scenegraph/ThreadTeam.h"
#include "throng/sim/ClipBlend.h"
#include "throng/sim/CounterRng.h"
#include "throng/sim/Ranks.h"

namespace throng::sim {
namespace {

constexpr float kPi = std::numbers::pi_v<float>;
// Message tags of a distributed step's four exchanges.
constexpr int kGhostTag = 101, kHandoverTag = 102, kWalkerTag = 103, kViewTag = 104;

// The view walkers are gathered near, as rank 0 sends it to the others each step.
struct GatherViewRecord {
    double planes[6][4] = {};   // (normal, offset) of each frustum plane, inside where n·p + d >= 0
    double margin = 0.0;        // metres a walker may stand outside and still be sent
    std::uint32_t active = 0;   // planes in use (bit i: plane i)
    std::uint32_t on = 0;       // 0: send every walker
};

// Whether a walker standing at `p` is within `view.margin` of the view (always, with no view).
bool nearView(const GatherViewRecord& view, const glm::vec3& p) {
    if (!view.on) return true;
    for (int i = 0; i < 6; ++i) {
        if (!(view.active & (1u << i))) continue;
        const double* q = view.planes[i];
        if (q[0] * double(p.x) + q[1] * double(p.y) + q[2] * double(p.z) + q[3] < -view.margin) return false;
    }
    return true;
}

float wrapAngle(float a) {
    while (a > kPi) a -= 2 * kPi;
    while (a < -kPi) a += 2 * kPi;
    return a;
}

// The farthest any part of `tmpl` gets from its Skeleton Root in pose `dofs`.
double farthestPart(const ActorTemplate& tmpl, std::span<const float> dofs) {
    std::vector<Affine> model(tmpl.nodeCount());
    std::vector<BoundingSphere> geometry(tmpl.nodeCount()), subtree(tmpl.nodeCount());
    computeModelTransforms(tmpl, dofs, {}, model);
    computeInternalSpheres(tmpl, model, {}, geometry, subtree);
    double far = 0.0;
    for (const BoundingSphere& g : geometry)
        if (g.valid()) far = std::max(far, glm::length(g.center()) + g.radius());
    return far;
}

}  // namespace

Locomotion::Locomotion(std::shared_ptr<const NavMesh> navMesh, Settings settings, std::vector<double> levelEnds,
                       EffectCounters* counters)
    : nav_(std::move(navMesh)), settings_(settings), levelEnds_(std::move(levelEnds)), counters_(counters) {
    if (!nav_) throw std::invalid_argument("Locomotion: argument 'navMesh' is null");
    for (std::size_t i = 0; i < levelEnds_.size(); ++i)
        if (std::isnan(levelEnds_[i]) || levelEnds_[i] <= 0.0 || (i > 0 && levelEnds_[i] <= levelEnds_[i - 1]))
            throw std::invalid_argument("Locomotion: level ends must be positive and increasing");
    if (settings_.avoidanceQuality < 0 || settings_.avoidanceQuality > 3)
        throw std::invalid_argument("Locomotion: avoidance quality must be 0 to 3, not " + std::to_string(settings_.avoidanceQuality));
    if (!(settings_.farDistance >= 0.0) || !std::isfinite(settings_.farDistance) || settings_.farEvery < 1 || settings_.farEvery > 1000)
        throw std::invalid_argument("Locomotion: far regions need a distance of 0 m or more and a rate of 1 to 1000 steps, not " +
                                    std::to_string(settings_.farDistance) + " m and " + std::to_string(settings_.farEvery));
    if (!(settings_.neighbourRange >= 1.0f) || !std::isfinite(settings_.neighbourRange))
        throw std::invalid_argument("Locomotion: the neighbour range must be at least 1 agent radius, not " +
                                    std::to_string(settings_.neighbourRange));
    if (counters_) {
        counters_->constructed("locomotion");
        if (settings_.avoidance) counters_->constructed("avoidance");
    }
}

Locomotion::~Locomotion() {
    for (Region& r : regions_) {
        dtFreeCrowd(r.crowd);
        dtFreeNavMeshQuery(r.query);
    }
}

std::uint32_t Locomotion::addActor(const Actor& a) {
    const std::string where = "Locomotion::addActor";
    if (started_) throw std::invalid_argument(where + ": actors must be added before the first frame");
    if (!a.tmpl) throw std::invalid_argument(where + ": argument 'actor.tmpl' is null");
    const auto clips = a.tmpl->clips();
    if (a.walkClip < 0 || std::size_t(a.walkClip) >= clips.size())
        throw std::invalid_argument(where + ": template '" + a.tmpl->name() + "' has no walk clip " + std::to_string(a.walkClip));
    if (a.runClip >= 0 && std::size_t(a.runClip) >= clips.size())
        throw std::invalid_argument(where + ": template '" + a.tmpl->name() + "' has no run clip " + std::to_string(a.runClip));
    if (!(a.walkClipSpeed > 0) || !(a.runClipSpeed > a.walkClipSpeed || a.runClip < 0) || !(a.speed > 0) ||
        !std::isfinite(a.speed) || !std::isfinite(a.walkClipSpeed) || !std::isfinite(a.runClipSpeed))
        throw std::invalid_argument(where + ": speeds must be positive, finite and the run clip's above the walk clip's");
    const auto onMesh = nav_->nearestPoint(a.start, glm::vec3(5.0f, 10.0f, 5.0f));
    if (!onMesh)
        throw std::invalid_argument(where + ": start (" + std::to_string(a.start.x) + ", " + std::to_string(a.start.y) + ", " +
                                    std::to_string(a.start.z) + ") is not near the navigation mesh");
    if (a.goal && !nav_->nearestPoint(*a.goal, glm::vec3(5.0f, 10.0f, 5.0f)))
        throw std::invalid_argument(where + ": goal (" + std::to_string(a.goal->x) + ", " + std::to_string(a.goal->y) + ", " +
                                    std::to_string(a.goal->z) + ") is not near the navigation mesh");
    State s;
    s.position = *onMesh;
    s.heading = static_cast<float>(CounterRng(settings_.seed, a.stream).uniform(~0ull, -kPi, kPi));
    // The Skeleton Root's extent and the blends' margin depend on the template and clips only:
    // measured once for each (a crowd of a million shares a handful).
    auto known = std::find_if(clipBounds_.begin(), clipBounds_.end(), [&](const ClipBounds& c) {
        return c.tmpl == a.tmpl.get() && c.walkClip == a.walkClip && c.runClip == a.runClip;
    });
    if (known == clipBounds_.end()) {
        ClipBounds bounds{a.tmpl.get(), a.walkClip, a.runClip, {}, 0.0};
        BoundingSphere extent(Vec3(0.0), 0.0);
        for (int clip : {a.walkClip, a.runClip}) {
            if (clip < 0) continue;
            const AnimationClip& c = *clips[std::size_t(clip)];
            for (int k = 0; k <= 240; ++k) extent.expandBy(Vec3(c.sampleRoot(c.duration() * k / 240.0, false).translation));
        }
        extent.inflate(0.01);
        bounds.extent = extent;
        // Blends of walk and run can reach beyond either clip: measure how far, over a few phases.
        if (a.runClip >= 0) {
            const AnimationClip &walk = *clips[std::size_t(a.walkClip)], &run = *clips[std::size_t(a.runClip)];
            std::vector<float> pw(a.tmpl->restDofs().begin(), a.tmpl->restDofs().end()), pr = pw, blend = pw;
            double worst = 0.0;
            for (int k = 0; k < 16; ++k) {
                walk.sample(*a.tmpl, walk.duration() * k / 16.0, true, {}, pw);
                run.sample(*a.tmpl, run.duration() * k / 16.0, true, {}, pr);
                for (float w : {0.25f, 0.5f, 0.75f}) {
                    blendPoses(*a.tmpl, pw, pr, w, {}, blend);
                    worst = std::max(worst, farthestPart(*a.tmpl, blend));
                }
            }
            bounds.blendMargin = std::max(0.0, worst - a.tmpl->skeletonRootRadius()) + 0.02;
        }
        clipBounds_.push_back(bounds);
        known = clipBounds_.end() - 1;
    }
    s.extent = known->extent;
    s.blendMargin = known->blendMargin;
    actors_.push_back(a);
    state_.push_back(s);
    return static_cast<std::uint32_t>(actors_.size() - 1);
}

void Locomotion::requestTarget(Region& region, std::uint32_t slot) {
    State& s = state_[slot];
    dtQueryFilter filter;
    const glm::vec3 extents(2.0f, 4.0f, 2.0f);
    dtPolyRef ref = 0;
    glm::vec3 snapped;
    region.query->findNearestPoly(&s.target.x, &extents.x, &filter, &ref, &snapped.x);
    if (ref) region.crowd->requestMoveTarget(s.agent, ref, &snapped.x);
}

void Locomotion::newDestination(Region& region, std::uint32_t slot) {
    State& s = state_[slot];
    const Actor& a = actors_[slot];
    if (a.goal && s.trips > 0) return;  // there, or on its way: a fixed goal is asked for once
    const CounterRng rng(settings_.seed, a.stream);
    bool found = false;
    if (!a.goal && settings_.destinationRange > 0.0) {
        // A few tries at a point within range that lies on the mesh; then anywhere.
        dtQueryFilter filter;
        const glm::vec3 extents(2.0f, 4.0f, 2.0f);
        for (std::uint64_t k = 0; k < 8 && !found; ++k) {
            const std::uint64_t c = (s.trips * 8 + k) * 2 + (std::uint64_t(1) << 40);  // apart from randomPoint's counters
            const glm::vec3 want = s.position + glm::vec3(float(rng.uniform(c, -1.0, 1.0) * settings_.destinationRange), 0.0f,
                                                          float(rng.uniform(c + 1, -1.0, 1.0) * settings_.destinationRange));
            dtPolyRef ref = 0;
            glm::vec3 snapped;
            region.query->findNearestPoly(&want.x, &extents.x, &filter, &ref, &snapped.x);
            if (ref) s.target = snapped, found = true;
        }
    }
    if (!found) s.target = a.goal ? *a.goal : nav_->randomPoint(rng, s.trips, *region.query);
    ++s.trips;
    requestTarget(region, slot);
}

int Locomotion::addAgent(Region& region, std::uint32_t r, std::uint32_t slot, const float* position, const float* velocity, bool ghost) {
    dtCrowdAgentParams p{};
    p.radius = settings_.radius;
    p.height = settings_.height;
    p.maxAcceleration = settings_.maxAcceleration;
    p.maxSpeed = static_cast<float>(actors_[slot].speed);
    p.collisionQueryRange = settings_.radius * settings_.neighbourRange;
    p.pathOptimizationRange = settings_.radius * 30.0f;
    // A ghost only stands in the way: it neither steers nor avoids, and its own move is discarded.
    p.updateFlags = ghost ? 0 : DT_CROWD_ANTICIPATE_TURNS | DT_CROWD_OPTIMIZE_VIS | DT_CROWD_OPTIMIZE_TOPO;
    if (settings_.avoidance && !ghost) p.updateFlags |= DT_CROWD_OBSTACLE_AVOIDANCE | DT_CROWD_SEPARATION;
    p.obstacleAvoidanceType = static_cast<unsigned char>(settings_.avoidanceQuality);
    p.separationWeight = 2.0f;
    const int agent = region.crowd->addAgent(position, &p);
    if (agent < 0)
        throw std::runtime_error("Locomotion: region " + std::to_string(r) + " is full (" + std::to_string(region.capacity) +
                                 " agents with its ghosts); declare smaller regions");
    if (velocity) {
        dtCrowdAgent* ag = region.crowd->getEditableAgent(agent);
        for (int k = 0; k < 3; ++k) ag->vel[k] = ag->dvel[k] = ag->nvel[k] = velocity[k];
        if (ghost) region.crowd->requestMoveVelocity(agent, velocity);  // it keeps going as it went
    }
    return agent;
}

void Locomotion::startRegion(std::uint32_t r) {
    Region& region = regions_[r];
    region.query = nav_->newQuery();
    region.crowd = dtAllocCrowd();
    if (!region.crowd || !region.crowd->init(region.capacity, settings_.radius, nav_->detourMesh()))
        throw std::runtime_error("Locomotion: DetourCrowd could not be initialised for " + std::to_string(region.capacity) +
                                 " agents in region " + std::to_string(r));
    // Avoidance quality: the adaptive sampling's divisions, rings and depth, from coarse to Detour's
    // own default (3); Detour's other weights stay as they are.
    static constexpr unsigned char kSampling[4][3] = {{5, 2, 1}, {5, 2, 2}, {7, 2, 3}, {7, 2, 5}};
    const int q = settings_.avoidanceQuality;
    dtObstacleAvoidanceParams params = *region.crowd->getObstacleAvoidanceParams(q);
    params.adaptiveDivs = kSampling[q][0];
    params.adaptiveRings = kSampling[q][1];
    params.adaptiveDepth = kSampling[q][2];
    region.crowd->setObstacleAvoidanceParams(q, &params);
    for (std::uint32_t slot : region.owned) {
        state_[slot].agent = addAgent(region, r, slot, &state_[slot].position.x, nullptr, false);
        newDestination(region, slot);
    }
}

void Locomotion::start() {
    started_ = true;
    const RegionGrid& grid = settings_.regions;
    if (grid.regionCount() > 1 && double(settings_.radius) * double(settings_.neighbourRange) >= grid.cellSize())
        throw std::invalid_argument("Locomotion: region cells of " + std::to_string(grid.cellSize()) +
                                    " m are narrower than the agents' collision range");
    regions_.resize(grid.regionCount());
    regionBounds_ = grid.regionBounds();
    pending_.assign(regions_.size(), 0.0);
    stepping_.assign(regions_.size(), 1);
    for (std::uint32_t slot = 0; slot < actors_.size(); ++slot) {
        State& s = state_[slot];
        s.region = grid.regionOf(s.position.x, s.position.z);
        regions_[s.region].owned.push_back(slot);
    }
    // Room for the agents a region starts with, its share of the crowd three times over (people
    // gather where destinations lie) and its ghosts; DetourCrowd numbers agents with 16 bits.
    const std::size_t share = actors_.size() / regions_.size();
    for (std::uint32_t r = 0; r < regions_.size(); ++r) {
        const std::size_t want = 3 * std::max(regions_[r].owned.size(), share) + 64;
        if (regions_[r].owned.size() > 40000)
            throw std::runtime_error("Locomotion: region " + std::to_string(r) + " starts with " + std::to_string(regions_[r].owned.size()) +
                                     " agents; DetourCrowd numbers a crowd's agents with 16 bits, so declare smaller regions");
        regions_[r].capacity = int(std::min<std::size_t>(want, 65000));
    }
    assignRanks();
    forEachChunk(endRegion_ - firstRegion_, 1, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t r = begin; r < end; ++r) startRegion(firstRegion_ + std::uint32_t(r));
    });
}

void Locomotion::distribute(Ranks& ranks) {
    if (started_) throw std::logic_error("Locomotion::distribute: the crowd has already started");
    ranks_ = &ranks;
}

void Locomotion::setGatherView(std::optional<Frustum> view, double margin) {
    if (!std::isfinite(margin) || margin < 0.0)
        throw std::invalid_argument("Locomotion::setGatherView: argument 'margin' must be finite and >= 0, not " + std::to_string(margin));
    gatherView_ = std::move(view);
    gatherMargin_ = margin;
}

void Locomotion::assignRanks() {
    const auto n = std::uint32_t(regions_.size());
    firstRegion_ = 0, endRegion_ = n;
    if (!ranks_) return;
    // Consecutive regions per rank (a region's ghosts and handovers then arrive in the order of
    // their sending region, as in one process), split so that the most walkers any rank starts with
    // is as small as it can be (the linear partition: the least load for which filling ranks in
    // order fits every region, by bisection).
    const auto size = std::size_t(ranks_->size());
    auto fill = [&](std::size_t most, bool assign) {  // ranks used when none takes more than `most`
        std::size_t rank = 0, load = 0;
        for (std::uint32_t r = 0; r < n; ++r) {
            const std::size_t w = regions_[r].owned.size();
            if (load > 0 && load + w > most && rank + 1 < size) ++rank, load = 0;
            load += w;
            if (assign) regionRank_[r] = int(rank);
        }
        return load <= most ? rank + 1 : size + 1;
    };
    std::size_t low = 0, high = actors_.size();
    for (std::uint32_t r = 0; r < n; ++r) low = std::max(low, regions_[r].owned.size());
    while (low < high) {
        const std::size_t mid = (low + high) / 2;
        if (fill(mid, false) <= size)
            high = mid;
        else
            low = mid + 1;
    }
    regionRank_.assign(n, 0);
    fill(low, true);
    const int me = ranks_->rank();
    firstRegion_ = std::uint32_t(std::lower_bound(regionRank_.begin(), regionRank_.end(), me) - regionRank_.begin());
    endRegion_ = std::uint32_t(std::upper_bound(regionRank_.begin(), regionRank_.end(), me) - regionRank_.begin());
}

template <class Record, class Deliver>
std::uint64_t Locomotion::route(std::vector<Record> Region::*list, std::uint32_t Record::*to, int tag, const char* what,
                                Deliver&& deliver) {
    // Every rank sends each other rank the records for its regions, in order of sending region;
    // each delivers what it received in order of sending rank, so of sending region.
    const auto size = std::size_t(ranks_->size());
    std::vector<std::vector<Record>> perRank(size);
    for (std::uint32_t r = firstRegion_; r < endRegion_; ++r)
        for (const Record& record : regions_[r].*list) perRank[std::size_t(regionRank_[record.*to])].push_back(record);
    std::vector<Bytes> outgoing(size);
    for (std::size_t k = 0; k < size; ++k) outgoing[k] = packRecords(std::span<const Record>(perRank[k]));
    const std::size_t sentBefore = ranks_->bytesSent();
    const std::vector<Bytes> incoming = ranks_->exchange(outgoing, tag, what);
    for (std::size_t k = 0; k < size; ++k)
        for (const Record& record : unpackRecords<Record>(incoming[k], int(k), what)) {
            if (record.slot >= actors_.size() || record.*to < firstRegion_ || record.*to >= endRegion_)
                throw RankError(int(k), "rank " + std::to_string(k) + " sent " + what + " for actor " + std::to_string(record.slot) +
                                            " in region " + std::to_string(record.*to) + ", which this rank does not step");
            deliver(record);
        }
    return ranks_->bytesSent() - sentBefore;
}

void Locomotion::exportGhosts(std::uint32_t r) {
    Region& region = regions_[r];
    region.ghostsOut.clear();
    if (regions_.size() == 1) return;
    const double margin = double(settings_.radius) * double(settings_.neighbourRange);  // the collision query range
    std::uint32_t near[8];
    for (std::uint32_t slot : region.owned) {
        const State& s = state_[slot];
        const int n = settings_.regions.regionsNear(s.position.x, s.position.z, margin, r, near);
        for (int k = 0; k < n; ++k) {
            GhostRecord g;
            g.slot = slot;
            g.region = near[k];
            for (int i = 0; i < 3; ++i) g.position[i] = s.position[i], g.velocity[i] = s.velocity[i];
            region.ghostsOut.push_back(g);
        }
    }
}

void Locomotion::importGhosts(std::uint32_t r) {
    Region& region = regions_[r];
    region.ghostAgents.clear();
    for (const GhostRecord& g : region.ghostsIn) region.ghostAgents.push_back(addAgent(region, r, g.slot, g.position, g.velocity, true));
}

void Locomotion::stepRegion(std::uint32_t r, float dt) {
    Region& region = regions_[r];
    if (!stepping_[r]) {  // a far region waiting for its turn: its walkers carry on as they went
        for (std::uint32_t slot : region.owned) state_[slot].position += state_[slot].velocity * dt;
        return;
    }
    dt = static_cast<float>(pending_[r]);  // the time since it last stepped
    pending_[r] = 0.0;
    for (std::uint32_t slot : region.owned) {
        const State& s = state_[slot];
        const glm::vec3 d = s.target - s.position;
        if (d.x * d.x + d.z * d.z < 1.0f) newDestination(region, slot);
    }
    importGhosts(r);
    region.crowd->update(dt, nullptr);
    for (int agent : region.ghostAgents) region.crowd->removeAgent(agent);
    for (std::uint32_t slot : region.owned) {
        State& s = state_[slot];
        const dtCrowdAgent* agent = region.crowd->getAgent(s.agent);
        s.position = glm::vec3(agent->npos[0], agent->npos[1], agent->npos[2]);
        s.velocity = glm::vec3(agent->vel[0], agent->vel[1], agent->vel[2]);
    }
}

void Locomotion::exportHandovers(std::uint32_t r) {
    Region& region = regions_[r];
    region.leaving.clear();
    if (regions_.size() == 1) return;
    for (std::uint32_t slot : region.owned) {
        const State& s = state_[slot];
        const std::uint32_t to = settings_.regions.regionOf(s.position.x, s.position.z);
        if (to == r) continue;
        HandoverRecord h;
        h.slot = slot;
        h.from = r;
        h.to = to;
        for (int i = 0; i < 3; ++i) h.position[i] = s.position[i], h.velocity[i] = s.velocity[i], h.target[i] = s.target[i];
        h.heading = s.heading, h.speed = s.speed, h.runWeight = s.runWeight, h.phase = s.phase, h.trips = s.trips;
        region.leaving.push_back(h);
        region.crowd->removeAgent(s.agent);
    }
}

void Locomotion::importHandovers(std::uint32_t r) {
    Region& region = regions_[r];
    if (region.leaving.empty() && region.arriving.empty()) return;
    // Arrivals join in order of slot, whichever region they come from.
    std::sort(region.arriving.begin(), region.arriving.end(), [](const HandoverRecord& a, const HandoverRecord& b) { return a.slot < b.slot; });
    for (const HandoverRecord& h : region.arriving) {
        State& s = state_[h.slot];  // as the record has it: it may come from another rank
        s.region = r;
        s.position = glm::vec3(h.position[0], h.position[1], h.position[2]);
        s.velocity = glm::vec3(h.velocity[0], h.velocity[1], h.velocity[2]);
        s.target = glm::vec3(h.target[0], h.target[1], h.target[2]);
        s.heading = h.heading, s.speed = h.speed, s.runWeight = h.runWeight, s.phase = h.phase, s.trips = h.trips;
        s.agent = addAgent(region, r, h.slot, h.position, h.velocity, false);
        requestTarget(region, h.slot);
    }
    // The slots it owns, still increasing: those that stayed merged with those that came.
    region.scratch.clear();
    std::size_t k = 0, gone = 0;
    for (std::uint32_t slot : region.owned) {
        if (gone < region.leaving.size() && region.leaving[gone].slot == slot) {  // left (listed in the same order)
            ++gone;
            continue;
        }
        while (k < region.arriving.size() && region.arriving[k].slot < slot) region.scratch.push_back(region.arriving[k++].slot);
        region.scratch.push_back(slot);
    }
    for (; k < region.arriving.size(); ++k) region.scratch.push_back(region.arriving[k].slot);
    region.owned.swap(region.scratch);
}

void Locomotion::advance(const FrameContext& context) {
    if (!started_) start();
    const float dt = static_cast<float>(context.deltaTime);
    if (dt <= 0.0f) return;
    const Stopwatch watch;
    RankStepRecord mine;
    // Which regions step now: every one, unless the scene lets far ones step less often.
    ++steps_;
    std::size_t deferred = 0;
    const double farSquared = settings_.farDistance * settings_.farDistance;
    for (std::uint32_t r = firstRegion_; r < endRegion_; ++r) {
        pending_[r] += context.deltaTime;
        bool now = true;
        if (settings_.farEvery > 1 && regions_.size() > 1) {
            const glm::dvec4& b = regionBounds_[r];
            const double dx = std::max({0.0, b.x - viewpoint_.x, viewpoint_.x - b.z});
            const double dz = std::max({0.0, b.y - viewpoint_.z, viewpoint_.z - b.w});
            now = dx * dx + dz * dz <= farSquared || (steps_ + r) % std::uint64_t(settings_.farEvery) == 0;
        }
        stepping_[r] = now;
        if (!now) deferred += regions_[r].owned.size();
    }
    lastDeferred_ = deferred;
    mine.deferred = deferred;
    auto eachRegion = [&](auto&& body) {
        forEachChunk(endRegion_ - firstRegion_, 1, [&](std::size_t, std::size_t begin, std::size_t end) {
            for (std::size_t r = begin; r < end; ++r) body(firstRegion_ + std::uint32_t(r));
        });
    };
    // Ghosts: every region lists its agents near another region; each region takes in what the
    // others sent it, in order of the sending region and then of slot.
    eachRegion([&](std::uint32_t r) { exportGhosts(r); });
    lastGhosts_ = 0;
    for (Region& region : regions_) region.ghostsIn.clear();
    if (!ranks_) {
        for (Region& region : regions_)
            for (const GhostRecord& g : region.ghostsOut) regions_[g.region].ghostsIn.push_back(g), ++lastGhosts_;
    } else {
        for (std::uint32_t r = firstRegion_; r < endRegion_; ++r)
            for (const GhostRecord& g : regions_[r].ghostsOut) ++mine.ghosts, mine.ghostsToRanks += regionRank_[g.region] != ranks_->rank();
        const Stopwatch wait;
        mine.borderBytes += route(&Region::ghostsOut, &GhostRecord::region, kGhostTag, "ghosts",
                                  [&](const GhostRecord& g) { regions_[g.region].ghostsIn.push_back(g); });
        mine.waitMs += wait.elapsedMs();
        lastGhosts_ = mine.ghosts;
    }
    eachRegion([&](std::uint32_t r) { stepRegion(r, dt); });
    // Handover: agents now in another region leave their crowd and join the other's.
    eachRegion([&](std::uint32_t r) { exportHandovers(r); });
    lastHandovers_ = 0;
    for (Region& region : regions_) region.arriving.clear();
    if (!ranks_) {
        for (Region& region : regions_)
            for (const HandoverRecord& h : region.leaving) regions_[h.to].arriving.push_back(h), ++lastHandovers_;
    } else {
        for (std::uint32_t r = firstRegion_; r < endRegion_; ++r)
            for (const HandoverRecord& h : regions_[r].leaving) {
                ++mine.handovers;
                if (regionRank_[h.to] != ranks_->rank())  // gone: this rank no longer steps it
                    ++mine.handedToRanks, state_[h.slot].region = h.to;
            }
        const Stopwatch wait;
        mine.borderBytes += route(&Region::leaving, &HandoverRecord::to, kHandoverTag, "handovers",
                                  [&](const HandoverRecord& h) { regions_[h.to].arriving.push_back(h); });
        mine.waitMs += wait.elapsedMs();
        lastHandovers_ = mine.handovers;
    }
    eachRegion([&](std::uint32_t r) { importHandovers(r); });
    if (counters_) {
        counters_->ticked("locomotion", actors_.size());
        if (settings_.avoidance) counters_->ticked("avoidance", actors_.size());
    }
    // Per agent, in parallel: each touches its own state only.
    if (!ranks_) {
        forEachChunk(actors_.size(), 256, [&](std::size_t, std::size_t begin, std::size_t end) {
            for (std::size_t slot = begin; slot < end; ++slot) walk(std::uint32_t(slot), context.deltaTime);
        });
        return;
    }
    ownSlots_.clear();
    for (std::uint32_t r = firstRegion_; r < endRegion_; ++r) ownSlots_.insert(ownSlots_.end(), regions_[r].owned.begin(), regions_[r].owned.end());
    forEachChunk(ownSlots_.size(), 256, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) walk(ownSlots_[k], context.deltaTime);
    });
    mine.agents = ownSlots_.size();
    mine.workMs = watch.elapsedMs() - mine.waitMs;
    gatherWalkers(mine);
}

void Locomotion::walk(std::uint32_t slot, double dt) {
    State& s = state_[slot];
    const Actor& a = actors_[slot];
    const glm::vec3 v(s.velocity.x, 0.0f, s.velocity.z);
    s.speed = glm::length(v);
    if (s.speed > 0.05f) {  // face the way it goes, turning at a bounded rate
        const float want = std::atan2(v.x, v.z);
        const float most = settings_.turnRate * static_cast<float>(dt);
        s.heading = wrapAngle(s.heading + std::clamp(wrapAngle(want - s.heading), -most, most));
    }
    // Speed matching: the walk cycle advances as far as the actor walked, in double with the
    // exact step (a float step runs the cycle 5e-8 fast: 2e-4 cycles in a million steps).
    const double walkDuration = a.tmpl->clips()[std::size_t(a.walkClip)]->duration();
    const double clipSpeed = a.runClip < 0 ? a.walkClipSpeed : a.walkClipSpeed + (a.runClipSpeed - a.walkClipSpeed) * s.runWeight;
    if (walkDuration > 0.0) s.phase = std::fmod(s.phase + dt * s.speed / (clipSpeed * walkDuration), 1.0);
    if (a.runClip >= 0) {
        const float u = std::clamp(float((s.speed - a.walkClipSpeed) / (a.runClipSpeed - a.walkClipSpeed)), 0.0f, 1.0f);
        s.runWeight = u * u * (3.0f - 2.0f * u);
    }
}

void Locomotion::gatherWalkers(RankStepRecord mine) {
    // Rank 0 tells the others which walkers to send: those near the frame's view, or every one.
    GatherViewRecord view;
    if (ranks_->rank() == 0 && gatherView_) {
        view.on = 1, view.margin = gatherMargin_, view.active = gatherView_->activePlanes();
        for (int i = 0; i < 6; ++i)
            for (int k = 0; k < 4; ++k) view.planes[i][k] = gatherView_->plane(i)[k];
    }
    {
        const Stopwatch wait;
        const Bytes bytes = ranks_->broadcast(packRecords(std::span<const GatherViewRecord>(&view, 1)), kViewTag, "view");
        const std::vector<GatherViewRecord> got = unpackRecords<GatherViewRecord>(bytes, 0, "the view");
        if (got.size() != 1) throw RankError(0, "rank 0 sent " + std::to_string(bytes.size()) + " bytes for the view, not one record");
        view = got[0];
        mine.waitMs += wait.elapsedMs();
    }
    // One message per rank: its share of the step, then a record per walker it sends, written in
    // place (a million walkers are 40 MB a step: not copied twice).
    // Rank 0's own walkers are up to date there: it sends none (and counts them all as sent).
    const bool root = ranks_->rank() == 0;
    std::size_t sent = 0;
    if (!root)
        for (std::uint32_t slot : ownSlots_) sent += nearView(view, state_[slot].position);
    mine.sent = root ? ownSlots_.size() : sent;
    Bytes message(sizeof(RankStepRecord) + sent * sizeof(WalkerRecord));
    std::memcpy(message.data(), &mine, sizeof mine);
    std::size_t k = 0;
    if (!root)
        for (std::uint32_t slot : ownSlots_) {
            const State& s = state_[slot];
            if (!nearView(view, s.position)) continue;
            WalkerRecord w;
            w.slot = slot, w.region = s.region;
            for (int i = 0; i < 3; ++i) w.position[i] = s.position[i];
            w.heading = s.heading, w.speed = s.speed, w.runWeight = s.runWeight, w.phase = s.phase;
            std::memcpy(message.data() + sizeof(RankStepRecord) + k++ * sizeof(WalkerRecord), &w, sizeof w);
        }
    const std::size_t sentBefore = ranks_->bytesSent();
    const std::vector<Bytes> gathered = ranks_->gather(message, kWalkerTag, "walkers");
    rankSteps_.assign(std::size_t(ranks_->size()), RankStepRecord{});
    if (!root) {
        mine.stateBytes = ranks_->bytesSent() - sentBefore;
        rankSteps_[std::size_t(ranks_->rank())] = mine;
        return;
    }
    // Rank 0: its own walkers are present, and those the others sent; the rest only with no view.
    present_.assign(state_.size(), view.on ? 0 : 1);
    for (std::uint32_t slot : ownSlots_) present_[slot] = 1;
    lastGhosts_ = lastHandovers_ = lastDeferred_ = 0;
    for (std::size_t r = 0; r < gathered.size(); ++r) {
        const Bytes& bytes = gathered[r];
        if (bytes.size() < sizeof(RankStepRecord) || (bytes.size() - sizeof(RankStepRecord)) % sizeof(WalkerRecord) != 0)
            throw RankError(int(r), "rank " + std::to_string(r) + " sent " + std::to_string(bytes.size()) +
                                        " bytes of walkers, not a step record and whole walker records");
        RankStepRecord& step = rankSteps_[r];
        std::memcpy(&step, bytes.data(), sizeof step);
        if (r > 0) step.stateBytes = bytes.size() + sizeof(std::uint64_t);  // and its size header
        lastGhosts_ += step.ghosts, lastHandovers_ += step.handovers, lastDeferred_ += step.deferred;
        if (r == 0) continue;  // rank 0's own walkers are already up to date
        const std::size_t n = (bytes.size() - sizeof(RankStepRecord)) / sizeof(WalkerRecord);
        for (std::size_t i = 0; i < n; ++i) {
            WalkerRecord w;
            std::memcpy(&w, bytes.data() + sizeof(RankStepRecord) + i * sizeof(WalkerRecord), sizeof w);
            if (w.slot >= state_.size() || w.region >= regions_.size())
                throw RankError(int(r), "rank " + std::to_string(r) + " sent a walker record for actor " + std::to_string(w.slot) +
                                            " in region " + std::to_string(w.region) + ", which do not exist");
            State& s = state_[w.slot];
            s.region = w.region;
            s.position = glm::vec3(w.position[0], w.position[1], w.position[2]);
            s.heading = w.heading, s.speed = w.speed, s.runWeight = w.runWeight, s.phase = w.phase;
            present_[w.slot] = 1;
        }
    }
    presentCount_ = 0;
    for (std::uint8_t p : present_) presentCount_ += p;
}

double Locomotion::clipTime(std::uint32_t slot, double) const {
    // The walk cycle's phase follows the distance walked, not the clock.
    const Actor& a = actors_[slot];
    return state_[slot].phase * a.tmpl->clips()[std::size_t(a.walkClip)]->duration();
}

namespace {
// A walker's Reference Point: at its position, facing its heading, given the heading's sine and cosine.
Mat4 walkerRefpoint(const Vec3& position, double sn, double c) {
    Mat4 m(1.0);
    m[0] = Vec4(c, 0.0, -sn, 0.0);
    m[2] = Vec4(sn, 0.0, c, 0.0);
    m[3] = Vec4(position, 1.0);
    return m;
}
}  // namespace

Mat4 Locomotion::referencePoint(std::uint32_t slot, const FrameContext&, OpTally* ops) {
    const State& s = state_[slot];
    double sn, c;
    detail::sinCos(double(s.heading), sn, c);
    THRONG_TALLY(ops, 0, 0, 0, 2);
    return walkerRefpoint(Vec3(s.position), sn, c);
}

void Locomotion::referencePoints(std::span<const std::uint32_t> slots, const FrameContext&, OpTally* ops, std::span<Mat4> out) {
    constexpr std::size_t kBlock = 16;
    double headings[kBlock], sines[kBlock], cosines[kBlock];
    for (std::size_t first = 0; first < slots.size(); first += kBlock) {
        const std::size_t n = std::min(kBlock, slots.size() - first);
        for (std::size_t k = 0; k < n; ++k) headings[k] = double(state_[slots[first + k]].heading);
        detail::sinCos(headings, sines, cosines, n);
        for (std::size_t k = 0; k < n; ++k) {
            THRONG_TALLY(ops, 0, 0, 0, 2);
            out[first + k] = walkerRefpoint(Vec3(state_[slots[first + k]].position), sines[k], cosines[k]);
        }
    }
}

RootPose Locomotion::skeletonRoot(std::uint32_t slot, double, int level, OpTally* ops) {
    if (level >= static_cast<int>(levelEnds_.size())) return RootPose{};
    const Actor& a = actors_[slot];
    const AnimationClip& walk = *a.tmpl->clips()[std::size_t(a.walkClip)];
    return walk.sampleRoot(state_[slot].phase * walk.duration(), true, ops, level >= 1);
}

void Locomotion::pose(std::uint32_t slot, double, int level, const ActorTemplate& tmpl,
                      std::span<const std::uint8_t> active, std::span<float> dofs, OpTally* ops) {
    const Actor& a = actors_[slot];
    const State& s = state_[slot];
    if (level >= static_cast<int>(levelEnds_.size())) {  // beyond the last band: rest pose
        writeRestPose(tmpl, active, dofs);
        return;
    }
    const AnimationClip& walk = *tmpl.clips()[std::size_t(a.walkClip)];
    walk.sample(tmpl, s.phase * walk.duration(), true, active, dofs, ops, level >= 1);
    if (a.runClip >= 0 && s.runWeight > 0.0f && level == 0) {  // blending is level-0 detail
        thread_local std::vector<float> run;
        run.assign(dofs.begin(), dofs.end());
        const AnimationClip& r = *tmpl.clips()[std::size_t(a.runClip)];
        r.sample(tmpl, s.phase * r.duration(), true, active, run, ops);
        blendPoses(tmpl, dofs, run, s.runWeight, active, dofs);
    }
}

}  // namespace throng::sim
