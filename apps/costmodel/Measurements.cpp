#include "Measurements.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <tuple>

#include "throng/actors/ActorProcessor.h"
#include "throng/research/CostModel.h"
#include "throng/research/CostModelScene.h"
#include "throng/actors/JointError.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/actors/Table3Template.h"
#include "throng/scenegraph/OpCounter.h"
#include "throng/testkit/TownSpread.h"

namespace throng::costmodel {
namespace {

CategoryFigures read(const OpCounter& c) {
    CategoryFigures f;
    for (std::size_t i = 0; i < kOpCategoryCount; ++i) {
        f.operations[i] = c.operations(static_cast<OpCategory>(i));
        f.fmult[i] = c.fmult(static_cast<OpCategory>(i));
        f.ops[i] = c.ops(static_cast<OpCategory>(i));
    }
    return f;
}

std::uint64_t at(const CategoryFigures& f, OpCategory c) { return f.fmult[static_cast<std::size_t>(c)]; }
std::uint64_t count(const CategoryFigures& f, OpCategory c) { return f.operations[static_cast<std::size_t>(c)]; }

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

// Memory the system can still give, from /proc/meminfo (0 when unknown).
std::size_t availableBytes() {
    std::ifstream in("/proc/meminfo");
    std::string key;
    std::size_t kb = 0;
    std::string unit;
    while (in >> key >> kb >> unit)
        if (key == "MemAvailable:") return kb * 1024;
    return 0;
}

}  // namespace

ExampleSceneFigures measureExampleScene() {
    Crowd crowd;
    const CostModelScene scene = buildCostModelScene(crowd, makeTable3Template(), std::make_shared<KeyframeBehaviour>());
    ActorProcessor p(crowd);
    p.counter().setEnabled(true);
    ExampleSceneFigures f;
    p.setProcessing(Processing::Traditional);
    f.traditionalStats = p.processFrame(*scene.root, scene.camera, scene.time);
    f.traditional = read(p.counter());
    p.setProcessing(Processing::Actor);
    f.actorStats = p.processFrame(*scene.root, scene.camera, scene.time);
    f.actor = read(p.counter());
    const double nodes = double(count(f.traditional, OpCategory::SkeletonMatrix));
    const double actors = double(f.traditionalStats.actorsInScene);
    f.averageCost = double(at(f.traditional, OpCategory::SkeletonDofValues)) / nodes;
    f.refpointCost = double(at(f.traditional, OpCategory::RefpointDofValues)) / actors;
    f.skeletonRootCost = double(at(f.traditional, OpCategory::SkeletonRootDofValues)) / actors;
    const double posedNodes = double(count(f.actor, OpCategory::SkeletonMatrix));
    f.averageCostActor = posedNodes > 0 ? double(at(f.actor, OpCategory::SkeletonDofValues)) / posedNodes : 0.0;
    f.kernels = measureKernels(scene, crowd, ProcessorSettings{}, p.drawList(), f.traditionalStats, f.actorStats);
    return f;
}

std::vector<WallClockRow> measureWallClock(const std::vector<std::size_t>& sizes, const Progress& progress) {
    // Per actor: the crowd's state (~1.2 kB for the Table 3 actor) and traditional processing's
    // per-node workspace (40 nodes x 240 bytes), with room to spare.
    constexpr std::size_t kBytesPerActor = 14 * 1024;
    const double averageCost = measureExampleScene().averageCost;
    std::vector<WallClockRow> rows;
    for (std::size_t n : sizes) {
        const std::size_t available = availableBytes();
        if (available && n * kBytesPerActor > available * 8 / 10) {
            progress("wall clock: skipping " + std::to_string(n) + " actors: about " +
                     std::to_string(n * kBytesPerActor >> 20) + " MiB needed, " + std::to_string(available >> 20) +
                     " MiB available");
            continue;
        }
        progress("wall clock: " + std::to_string(n) + " actors");
        Crowd crowd;
        const CostModelScene scene = buildTable2Scene(crowd, n);
        ActorProcessor p(crowd);
        WallClockRow row;
        row.actors = n;
        // A counted frame of each for the FMULT ratio (also warms every allocation up).
        p.counter().setEnabled(true);
        p.setProcessing(Processing::Traditional);
        const double tradFmult = double(p.processFrame(*scene.root, scene.camera, scene.time).fmultTotal);
        p.setProcessing(Processing::Actor);
        const ActorFrameStatistics& counted = p.processFrame(*scene.root, scene.camera, scene.time);
        row.fmultFactor = tradFmult / double(counted.fmultTotal);
        row.posed = counted.actorsPosed;
        p.counter().setEnabled(false);
        const int repeats = n <= 10'000 ? 9 : n <= 100'000 ? 3 : 1;
        std::vector<double> trad, act;
        for (int r = 0; r < repeats; ++r) {
            p.setProcessing(Processing::Traditional);
            trad.push_back(p.processFrame(*scene.root, scene.camera, scene.time).appCullMs());
            p.setProcessing(Processing::Actor);
            act.push_back(p.processFrame(*scene.root, scene.camera, scene.time).appCullMs());
        }
        row.traditionalMs = median(trad);
        row.actorMs = median(act);
        row.timeFactor = row.traditionalMs / row.actorMs;
        CostModelFactors factors;
        factors.nActors = double(n);
        row.modelFactor = CostModel(factors).improvementFactor(averageCost, 1.0, 1.0);
        row.publishedFactor = CostModel::publishedImprovementFactor(averageCost, 1.0, 1.0);
        rows.push_back(row);
    }
    return rows;
}

std::vector<AccuracyRow> measureAccuracy(const std::vector<double>& scales, const Progress& progress) {
    Crowd crowd;
    const testkit::TownSpread town = testkit::buildTownSpread(crowd, kAccuracyActors, 400.0);
    ActorProcessor p(crowd);
    const double time = 1.234;  // between keys, so holding keys is an approximation
    const Crowd::State& s = crowd.state();
    using Key = std::tuple<const void*, std::uint32_t, std::uint32_t, const void*>;
    auto primitives = [&]() {
        std::set<Key> keys;
        for (const DrawItem& i : p.drawList().items()) keys.emplace(i.node, i.instance, i.part, i.drawable);
        return keys;
    };
    // Joint positions (world) of every posed actor, with inactive nodes at rest as they are drawn.
    auto jointPositions = [&](double lodScale) {
        std::map<ActorId, std::vector<Vec3>> out;
        for (ActorId id = 0; id < crowd.size(); ++id) {
            const ActorClass c = s.actorClass[id];
            if (c != ActorClass::B && c != ActorClass::C2 && c != ActorClass::C3_1 && c != ActorClass::C3_2) continue;
            const ActorTemplate& t = *s.tmpl[id];
            std::vector<std::uint8_t> active(t.nodeCount());
            computeActiveNodes(t, detailDistanceSquared(s.sklsWorld[id], town.camera.eye(), lodScale * lodScale, s.priority[id]), active);
            std::vector<float> dofs(crowd.dofs(id).begin(), crowd.dofs(id).end());
            for (std::size_t i = 0; i < t.nodeCount(); ++i)
                if (!active[i]) {
                    const std::uint32_t b = t.dofOffset(i), e = i + 1 < t.nodeCount() ? t.dofOffset(i + 1) : t.dofValueCount();
                    std::copy(t.restDofs().begin() + b, t.restDofs().begin() + e, dofs.begin() + b);
                }
            std::vector<Affine> model(t.nodeCount());
            computeModelTransforms(t, dofs, {}, model);
            std::vector<Vec3>& joints = out[id];
            for (const Affine& m : model) joints.push_back(Vec3(s.sklsWorld[id] * Vec4(Vec3(m.translation), 1.0)));
        }
        return out;
    };
    auto run = [&](double scale) {
        p.setLodScale(scale);
        std::vector<double> ms;
        ActorFrameStatistics last;
        for (int r = 0; r < 7; ++r) {
            last = p.processFrame(*town.root, town.camera, time);
            ms.push_back(last.appCullMs());
        }
        return std::make_pair(median(ms), last);
    };
    progress("accuracy: full detail");
    constexpr double kFullDetail = 1e-6;  // every distance ~0: every node active, every behaviour at level 0
    run(kFullDetail);
    const auto reference = jointPositions(kFullDetail);
    const auto referencePrimitives = primitives();
    std::vector<AccuracyRow> rows;
    std::vector<double> sweep = {kFullDetail};  // the reference itself comes first: no error, all identical
    sweep.insert(sweep.end(), scales.begin(), scales.end());
    for (double scale : sweep) {
        progress("accuracy: LOD scale " + std::to_string(scale));
        const auto [ms, stats] = run(scale);
        AccuracyRow row;
        row.lodScale = scale;
        row.appCullMs = ms;
        row.nodesEvaluated = stats.skeletonNodesEvaluated;
        row.primitives = stats.primitives;
        const auto joints = jointPositions(scale);
        JointError error;
        for (const auto& [id, positions] : joints) {
            const auto ref = reference.find(id);
            if (ref != reference.end()) error.add(positions, ref->second);
        }
        row.meanErrorMm = error.meanMm();
        row.maxErrorMm = error.maxMm();
        const auto drawn = primitives();
        std::size_t same = 0;
        for (const Key& k : referencePrimitives) same += drawn.count(k);
        row.identicalShare = referencePrimitives.empty() ? 1.0 : double(same) / double(referencePrimitives.size());
        rows.push_back(row);
    }
    return rows;
}

}  // namespace throng::costmodel
