// The town crowd under both processing methods (seed 002 §7: 2000 actors at 50 fps, 6000 at 25):
// APP+CULL time per frame for several crowd sizes, traditional and actor processing run on the
// very same frames side by side, then end-to-end headless frames per second (simulation, APP,
// CULL, DRAW and reading the image back) at 1280 x 720. Prints a Markdown table; --csv writes one.
//
// usage: bench_town [--actors 2000,6000,10000] [--frames N] [--draw-frames N] [--csv FILE] [--scene FILE]

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "throng/actors/ActorProcessor.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/GlRenderer.h"
#include "throng/sim/ScaleActors.h"
#include "throng/sim/SceneParser.h"
#include "throng/sim/Simulation.h"
#include "throng/sim/SimulationClock.h"

using namespace throng;

namespace {

struct Options {
    std::vector<std::int64_t> actors{2000, 6000, 10000};
    int frames = 120;       // compared frames per size
    int warmup = 60;        // frames simulated first, so walkers have spread out along the streets
    int drawFrames = 120;   // frames of the end-to-end run
    std::string csv;
    std::string scene = THRONG_TOWN_DEFAULT_SCENE;
};

struct Row {
    std::int64_t actors = 0;
    double traditionalMs = 0, actorMs = 0, stepMs = 0, posed = 0, nodesTraditional = 0, nodesActor = 0;
};

[[noreturn]] void usage(const std::string& problem) {
    std::fprintf(stderr, "bench_town: %s\nusage: bench_town [--actors 2000,6000,10000] [--frames N] [--draw-frames N] [--csv FILE] [--scene FILE]\n",
                 problem.c_str());
    std::exit(2);
}

Options parse(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (i + 1 >= argc) usage(a + " needs a value");
        const std::string v = argv[++i];
        if (a == "--actors") {
            o.actors.clear();
            std::stringstream s(v);
            for (std::string item; std::getline(s, item, ',');) {
                const long long n = std::atoll(item.c_str());
                if (n <= 0) usage("--actors expects positive counts separated by commas, got '" + v + "'");
                o.actors.push_back(n);
            }
        } else if (a == "--frames" || a == "--draw-frames") {
            const int n = std::atoi(v.c_str());
            if (n <= 0) usage(a + " expects a positive number, got '" + v + "'");
            (a == "--frames" ? o.frames : o.drawFrames) = n;
        } else if (a == "--csv") {
            o.csv = v;
        } else if (a == "--scene") {
            o.scene = v;
        } else {
            usage("unknown option '" + a + "'");
        }
    }
    return o;
}

std::unique_ptr<sim::Simulation> buildWorld(const Options& o, std::int64_t actors) {
    sim::SceneDescription scene = sim::parseSceneFile(o.scene);
    sim::scaleActors(scene, actors);
    return sim::Simulation::build(std::move(scene));
}

// Traditional and actor processing of the same frames: at each time the traditional frame runs
// first (it takes the behaviours' shared step, reported apart), then the actor frame.
Row compare(const Options& o, std::int64_t actors) {
    auto world = buildWorld(o, actors);
    ActorProcessor traditional(world->crowd()), actor(world->crowd());
    traditional.setProcessing(Processing::Traditional);
    actor.setProcessing(Processing::Actor);
    sim::SimulationClock clock(world->description().step);
    const double aspect = 1280.0 / 720.0;
    for (int f = 0; f < o.warmup; ++f, clock.advance()) actor.processFrame(world->root(), world->camera().at(clock.time(), aspect), clock.time());
    Row row;
    row.actors = std::int64_t(world->crowd().size());
    for (int f = 0; f < o.frames; ++f, clock.advance()) {
        const Camera camera = world->camera().at(clock.time(), aspect);
        const ActorFrameStatistics& t = traditional.processFrame(world->root(), camera, clock.time());
        row.traditionalMs += t.appCullMs();
        row.stepMs += t.stepMs;
        row.nodesTraditional += double(t.skeletonNodesEvaluated);
        const ActorFrameStatistics& a = actor.processFrame(world->root(), camera, clock.time());
        row.actorMs += a.appCullMs();
        row.posed += double(a.actorsPosed);
        row.nodesActor += double(a.skeletonNodesEvaluated);
    }
    const double n = o.frames;
    for (double* v : {&row.traditionalMs, &row.actorMs, &row.stepMs, &row.posed, &row.nodesTraditional, &row.nodesActor}) *v /= n;
    return row;
}

// Frames per second of the whole loop, drawn off screen at 1280 x 720 and read back.
double endToEndFps(const Options& o, std::int64_t actors, double* appCullMs, double* drawMs) {
    auto world = buildWorld(o, actors);
    auto context = createContext({.width = 1280, .height = 720, .window = false});
    GlRenderer renderer(context);
    ActorProcessor processor(world->crowd());
    sim::SimulationClock clock(world->description().step);
    const double aspect = 1280.0 / 720.0;
    for (int f = 0; f < o.warmup; ++f, clock.advance()) processor.processFrame(world->root(), world->camera().at(clock.time(), aspect), clock.time());
    *appCullMs = *drawMs = 0.0;
    const auto start = std::chrono::steady_clock::now();
    for (int f = 0; f < o.drawFrames; ++f, clock.advance()) {
        const ActorFrameStatistics& s = processor.processFrame(world->root(), world->camera().at(clock.time(), aspect), clock.time(), &renderer);
        (void)renderer.readFrame();  // waits for the frame, as writing it out would
        *appCullMs += s.appCullMs();
        *drawMs += s.drawMs;
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    *appCullMs /= o.drawFrames;
    *drawMs /= o.drawFrames;
    return o.drawFrames / seconds;
}

}  // namespace

int main(int argc, char** argv) {
    const Options o = parse(argc, argv);
    std::vector<Row> rows;
    try {
        for (std::int64_t n : o.actors) {
            std::fprintf(stderr, "bench_town: %lld actors, %d frames of each method...\n", (long long)n, o.frames);
            rows.push_back(compare(o, n));
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_town: %s\n", e.what());
        return 1;
    }
    std::printf("| actors | traditional APP+CULL ms | actor APP+CULL ms | speed-up | actors posed | Skeleton nodes trad / actor | shared step ms |\n");
    std::printf("|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const Row& r : rows)
        std::printf("| %lld | %.2f | %.2f | %.1f | %.0f | %.0f / %.0f | %.2f |\n", (long long)r.actors, r.traditionalMs, r.actorMs,
                    r.traditionalMs / r.actorMs, r.posed, r.nodesTraditional, r.nodesActor, r.stepMs);
    if (!o.csv.empty()) {
        std::ofstream csv(o.csv);
        csv << "actors,traditional_app_cull_ms,actor_app_cull_ms,speedup,posed,nodes_traditional,nodes_actor,step_ms\n";
        for (const Row& r : rows)
            csv << r.actors << ',' << r.traditionalMs << ',' << r.actorMs << ',' << r.traditionalMs / r.actorMs << ',' << r.posed << ','
                << r.nodesTraditional << ',' << r.nodesActor << ',' << r.stepMs << '\n';
    }
    try {
        std::fprintf(stderr, "bench_town: end to end, %lld actors at 1280 x 720, %d frames...\n", (long long)o.actors.front(), o.drawFrames);
        double appCull = 0, draw = 0;
        const double fps = endToEndFps(o, o.actors.front(), &appCull, &draw);
        std::printf("\nEnd to end, headless 1280 x 720, %lld actors (actor processing, one thread): %.1f fps "
                    "(APP+CULL %.2f ms, DRAW %.2f ms per frame)\n", (long long)o.actors.front(), fps, appCull, draw);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_town: end-to-end run failed: %s\n", e.what());
        return 1;
    }
    return 0;
}
