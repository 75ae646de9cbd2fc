// What the actors rank 0 of an MPI run does not show cost its APP and CULL. Rank 0 holds every
// walker of the town, but this frame's state only of those the other ranks sent, near the view; the
// cascade skips the rest unread (Behaviour::presence). One process stands in for rank 0 here: N
// walking humanoids in one group with a roaming bound (as the town's walkers), of which only those
// within a margin of the view are present, against those same walkers alone (a crowd holding nothing
// else), and against the whole crowd present (one process of the whole town). Same camera, same
// time, one frame of each per iteration, back to back, so noise touches them alike. A fourth crowd
// stands for rank 0 when every rank poses the walkers it steps (throng-town --pose-on-ranks): of
// the walkers near the view, only those on its side of the view's axis (its half of the view) are
// present. The
// walkers are numbered either in the order of where they start along a Z curve, as the town numbers
// its walkers (second argument 1), or at random (0), as the town numbered them before: a view's
// walkers then lie scattered among the others in every per-actor array.
//
// Counters: rank0_ms (the crowd with only the walkers near the view present), alone_ms (those
// walkers alone), whole_ms (every walker present), rank0_over_alone, present, actors and
// draw_items (which must be the same for rank0 and alone, or the run stops with an error);
// posing_ms (only rank 0's half of those near the view present), posing_over_alone, posing_present
// and posing_draw_items (fewer than draw_items, more than none, or the run stops).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "throng/actors/ActorGroup.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/SeedHumanoid.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/ZOrder.h"
#include "throng/testkit/TownSpread.h"

using namespace throng;

namespace {

// Key-frame walkers of which only some are present in this process (see Behaviour::presence).
class SomePresent : public KeyframeBehaviour {
public:
    std::vector<std::uint8_t> here;      // per slot, 1 when present; empty: every one
    std::vector<std::uint32_t> hereList;  // the present slots, increasing (as rank 0's exchange lists them)
    bool presence(std::span<const std::uint32_t> slots, std::span<std::uint8_t> present) const override {
        if (here.empty()) return true;
        for (std::size_t k = 0; k < slots.size(); ++k) present[k] = here[slots[k]];
        return false;
    }
    std::optional<std::span<const std::uint32_t>> presentSlots() const override {
        if (here.empty()) return std::nullopt;
        return std::span<const std::uint32_t>(hereList);
    }
};

// A crowd of walkers in one group whose roaming bound is the square they walk on.
struct Walkers {
    Crowd crowd;
    std::shared_ptr<SomePresent> behaviour = std::make_shared<SomePresent>();
    std::shared_ptr<Group> root = std::make_shared<Group>();
};

// `actors` seed humanoids walking circles over a square of side `extent` (as testkit's town spread),
// at random or in Z order of where they start.
std::vector<KeyframeBehaviour::Actor> spread(std::size_t actors, double extent, bool zOrdered) {
    static const auto humanoid = makeSeedHumanoid();
    std::mt19937_64 rng(1);
    std::vector<KeyframeBehaviour::Actor> all = testkit::circleWalkers(humanoid, std::max(humanoid->findClip("walk"), 0), actors, extent, rng);
    if (zOrdered)
        std::stable_sort(all.begin(), all.end(), [](const KeyframeBehaviour::Actor& p, const KeyframeBehaviour::Actor& q) {
            return zOrder(p.position.x, p.position.z, 16.0) < zOrder(q.position.x, q.position.z, 16.0);
        });
    return all;
}

std::unique_ptr<Walkers> walkers(const std::vector<KeyframeBehaviour::Actor>& actors, double extent) {
    auto w = std::make_unique<Walkers>();
    std::vector<ActorId> ids;
    for (const KeyframeBehaviour::Actor& a : actors) ids.push_back(w->crowd.add(a.tmpl, w->behaviour, w->behaviour->addActor(a)));
    auto group = w->crowd.makeGroupNode(std::move(ids));
    group->setRoamingBound(BoundingSphere(Vec3(0.0), extent));
    w->root->addChild(group);
    return w;
}

// Whether `p` lies within `margin` of every plane of `view`.
bool nearView(const Frustum& view, const Vec3& p, double margin) {
    for (int i = 0; i < Frustum::kPlaneCount; ++i)
        if ((view.activePlanes() & (1u << i)) && glm::dot(Vec3(view.plane(i)), p) + view.plane(i).w < -margin) return false;
    return true;
}

void BM_AbsentActors(benchmark::State& state) {
    const auto actors = std::size_t(state.range(0));
    const double extent = 6.3 * std::sqrt(double(actors));  // 2 km at 100k: a view sees about a third, as in the town
    const double time = 1.0, margin = 6.0;  // about the town's shown margin (summary.json)
    Camera camera;
    camera.setPerspective(1.0, 16.0 / 9.0, 0.1, 1500.0);
    camera.setLookAt(Vec3(0, 1.7, 0), Vec3(100, 1.7, 20), Vec3(0, 1, 0));
    const std::vector<KeyframeBehaviour::Actor> all = spread(actors, extent, state.range(1) != 0);
    auto whole = walkers(all, extent);
    ActorProcessor wholeProcessor(whole->crowd);
    wholeProcessor.processFrame(*whole->root, camera, time);
    // Present: the walkers standing within the margin of the view at this time, as rank 0 gets them.
    std::vector<std::uint8_t> here(actors, 0);
    std::vector<KeyframeBehaviour::Actor> near;
    for (std::size_t i = 0; i < actors; ++i)
        if (nearView(camera.frustum(), Vec3(whole->crowd.state().refWorld[i][3]), margin)) here[i] = 1, near.push_back(all[i]);
    std::vector<std::uint32_t> hereList;
    for (std::size_t i = 0; i < actors; ++i)
        if (here[i]) hereList.push_back(std::uint32_t(i));
    // Posing where stepped: rank 0's half of them, those on one side of the view's axis.
    std::vector<std::uint8_t> mine(actors, 0);
    std::vector<std::uint32_t> mineList;
    for (std::size_t i : hereList) {
        const Vec3 p(whole->crowd.state().refWorld[i][3]);
        if (p.z * 100.0 - p.x * 20.0 < 0.0) mine[i] = 1, mineList.push_back(std::uint32_t(i));
    }
    auto alone = walkers(near, extent);
    ActorProcessor aloneProcessor(alone->crowd);

    // A processor of its own for the half, so that each keeps its own frame-to-frame state.
    ActorProcessor halfProcessor(whole->crowd);
    enum Present { Near, Half, All };
    auto frame = [&](ActorProcessor& p, Walkers& w, Present present, double t) {
        w.behaviour->here = present == Near ? here : present == Half ? mine : std::vector<std::uint8_t>();
        w.behaviour->hereList = present == Near ? hereList : present == Half ? mineList : std::vector<std::uint32_t>();
        return p.processFrame(*w.root, camera, t);
    };
    for (int k = 0; k < 4; ++k) {  // draw lists grown, storage merged: timed frames do not allocate
        frame(wholeProcessor, *whole, Near, time);
        frame(aloneProcessor, *alone, All, time);
        frame(halfProcessor, *whole, Half, time);
        frame(wholeProcessor, *whole, All, time);
    }
    double later[2][5] = {}, early[2][3] = {};
    double rank0 = 0.0, lone = 0.0, everyone = 0.0, items = 0.0, posing = 0.0, posingItems = 0.0;
    std::int64_t frames = 0;
    for (auto _ : state) {
        const double t = time + double(frames % 2) * 1e-9;
        const ActorFrameStatistics a = frame(wholeProcessor, *whole, Near, t);
        const ActorFrameStatistics b = frame(aloneProcessor, *alone, All, t);
        const ActorFrameStatistics h = frame(halfProcessor, *whole, Half, t);
        if (h.drawItems == 0 || h.drawItems >= b.drawItems) {
            state.SkipWithError("rank 0's half of the walkers near the view drew none, or as many as all of them");
            return;
        }
        posing += h.appCullMs(), posingItems += double(h.drawItems);
        if (a.drawItems != b.drawItems || a.actorsPosed != b.actorsPosed) {
            state.SkipWithError("the crowd with only the walkers near the view present drew otherwise than those walkers alone");
            return;
        }
        rank0 += a.appCullMs(), lone += b.appCullMs(), items += double(a.drawItems);
        for (int k = 0; k < 2; ++k) {
            const ActorFrameStatistics& s = k == 0 ? a : b;
            const double before[3] = {s.refpointMs, s.matricesBoundsMs, s.cullMs};
            for (int i = 0; i < 3; ++i) early[k][i] += before[i];
            const double phases[5] = {s.skeletonRootMs, s.cull2Ms, s.poseMs, s.cull3Ms, s.drawListMs};
            for (int i = 0; i < 5; ++i) later[k][i] += phases[i];
        }
        everyone += frame(wholeProcessor, *whole, All, t).appCullMs();
        ++frames;
    }
    const double n = double(frames);
    state.counters["actors"] = double(actors);
    state.counters["z_order"] = double(state.range(1));
    state.counters["present"] = double(near.size());
    state.counters["draw_items"] = items / n;
    state.counters["rank0_ms"] = rank0 / n;
    state.counters["alone_ms"] = lone / n;
    state.counters["whole_ms"] = everyone / n;
    state.counters["rank0_over_alone"] = rank0 / lone;
    state.counters["posing_present"] = double(mineList.size());
    state.counters["posing_draw_items"] = posingItems / n;
    state.counters["posing_ms"] = posing / n;
    state.counters["posing_over_alone"] = posing / lone;
    // Where the time goes: before CULL 2 (phase 1, placement, CULL 1), then from CULL 2 on.
    const char* first[3] = {"refpoint", "bounds", "cull1"};
    for (int i = 0; i < 3; ++i) {
        state.counters[std::string("rank0_") + first[i] + "_ms"] = early[0][i] / n;
        state.counters[std::string("alone_") + first[i] + "_ms"] = early[1][i] / n;
    }
    const char* names[5] = {"sklsroot", "cull2", "pose", "cull3", "drawlist"};
    for (int i = 0; i < 5; ++i) {
        state.counters[std::string("rank0_") + names[i] + "_ms"] = later[0][i] / n;
        state.counters[std::string("alone_") + names[i] + "_ms"] = later[1][i] / n;
    }
}

BENCHMARK(BM_AbsentActors)->Unit(benchmark::kMillisecond)->Args({10000, 1})->MinTime(2.0);
BENCHMARK(BM_AbsentActors)->Unit(benchmark::kMillisecond)->Args({100000, 1})->Iterations(10);
BENCHMARK(BM_AbsentActors)->Unit(benchmark::kMillisecond)->Args({100000, 0})->Iterations(10);

}  // namespace

BENCHMARK_MAIN();
