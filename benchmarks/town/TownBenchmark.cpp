// The town crowd under both processing methods (seed 002 §7: 2000 actors at 50 fps, 6000 at 25):
// APP+CULL time per frame for several crowd sizes, traditional processing, actor processing, and
// actor processing with far actors as impostors, run on the very same frames side by side, from
// two cameras of the default scene's path: in a street (eye 2.5-3 m up, as in the seed's walk
// through Performer Town) and over the town (every actor in view). Then end-to-end headless
// frames per second (simulation, APP, CULL, DRAW and reading the image back) at 1280 x 720.
// Prints a Markdown table; --csv writes one.
//
// usage: bench_town [--actors 2000,6000,10000] [--frames N] [--draw-frames N] [--csv FILE] [--scene FILE]

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "throng/actors/ActorProcessor.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/GlRenderer.h"
#include "throng/scenegraph/Stopwatch.h"
#include "TownImpostors.h"
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

// The two cameras: times on the default scene's camera path.
struct View {
    const char* name;
    double pathTime;
};
constexpr View kViews[] = {{"street", 9.0}, {"overview", 0.0}};

struct Row {
    std::int64_t actors = 0;
    const char* view = "";
    double traditionalMs = 0, actorMs = 0, impostorMs = 0, stepMs = 0, posed = 0, posedWithImpostors = 0, impostors = 0;
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

// The impostor distance of the scene (40 m when it sets none) and its hysteresis in metres.
std::pair<double, double> impostorDistance(const sim::Simulation& world) {
    const auto& r = world.description().representation;
    const double distance = r.impostorDistance > 0.0 ? r.impostorDistance : 40.0;
    return {distance, r.hysteresis * distance};
}

// The three methods on the same frames: at each time traditional processing runs first (it takes
// the behaviours' shared step, reported apart), then actor processing, then actor processing with
// impostors. The simulation runs from t = 0; the camera stays at `view`.
Row compare(const Options& o, std::int64_t actors, const View& view) {
    auto world = buildWorld(o, actors);
    ActorProcessor traditional(world->crowd()), actor(world->crowd()), hybrid(world->crowd());
    traditional.setProcessing(Processing::Traditional);
    // Baked as throng-town bakes them; small cells, since APP+CULL only refers to them.
    town::TownImpostors impostors(createContext({.width = 32, .height = 32, .window = false}), *world, 32, {});
    const auto [distance, hysteresis] = impostorDistance(*world);
    impostors.attach(hybrid, distance, hysteresis);
    sim::SimulationClock clock(world->description().step);
    const Camera camera = world->camera().at(view.pathTime, 1280.0 / 720.0);
    for (int f = 0; f < o.warmup; ++f, clock.advance()) actor.processFrame(world->root(), camera, clock.time());
    Row row;
    row.actors = std::int64_t(world->crowd().size());
    row.view = view.name;
    for (int f = 0; f < o.frames; ++f, clock.advance()) {
        const ActorFrameStatistics& t = traditional.processFrame(world->root(), camera, clock.time());
        row.traditionalMs += t.appCullMs();
        row.stepMs += t.stepMs;
        const ActorFrameStatistics& a = actor.processFrame(world->root(), camera, clock.time());
        row.actorMs += a.appCullMs();
        row.posed += double(a.actorsPosed);
        const ActorFrameStatistics& h = hybrid.processFrame(world->root(), camera, clock.time());
        row.impostorMs += h.appCullMs();
        row.posedWithImpostors += double(h.actorsPosed);
        row.impostors += double(h.impostors);
    }
    const double n = o.frames;
    for (double* v : {&row.traditionalMs, &row.actorMs, &row.impostorMs, &row.stepMs, &row.posed, &row.posedWithImpostors, &row.impostors}) *v /= n;
    return row;
}

// Frames per second of the whole loop as throng-town runs it (impostors beyond the scene's
// distance), drawn off screen at 1280 x 720 and read back, the camera at `view`.
double endToEndFps(const Options& o, std::int64_t actors, const View& view, double* appCullMs, double* drawMs) {
    auto world = buildWorld(o, actors);
    auto context = createContext({.width = 1280, .height = 720, .window = false});
    town::TownImpostors impostors(context, *world, 64, {});
    GlRenderer renderer(context);
    ActorProcessor processor(world->crowd());
    const auto [distance, hysteresis] = impostorDistance(*world);
    impostors.attach(processor, distance, hysteresis);
    sim::SimulationClock clock(world->description().step);
    const Camera camera = world->camera().at(view.pathTime, 1280.0 / 720.0);
    for (int f = 0; f < o.warmup; ++f, clock.advance()) processor.processFrame(world->root(), camera, clock.time());
    *appCullMs = *drawMs = 0.0;
    const auto start = std::chrono::steady_clock::now();
    for (int f = 0; f < o.drawFrames; ++f, clock.advance()) {
        const ActorFrameStatistics& s = processor.processFrame(world->root(), camera, clock.time());
        Stopwatch watch;
        renderer.beginFrame(camera);
        renderer.draw(processor.drawList());
        impostors.draw(processor.drawList(), camera, clock.time());
        renderer.endFrame();
        (void)renderer.readFrame();  // waits for the frame, as writing it out would
        *drawMs += watch.elapsedMs();
        *appCullMs += s.appCullMs();
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
        for (std::int64_t n : o.actors)
            for (const View& view : kViews) {
                std::fprintf(stderr, "bench_town: %lld actors, %s camera, %d frames of each method...\n", (long long)n, view.name, o.frames);
                rows.push_back(compare(o, n, view));
            }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_town: %s\n", e.what());
        return 1;
    }
    std::printf("APP+CULL per frame, one thread (ms); the behaviours' shared step (navigation, flocking) is the same for all and reported apart.\n\n");
    std::printf("| actors | camera | traditional | actor | actor + impostors | speed-up (actor / + impostors) | posed (actor / + impostors) | impostors | shared step |\n");
    std::printf("|---:|---|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const Row& r : rows)
        std::printf("| %lld | %s | %.2f | %.2f | %.2f | %.1f / %.1f | %.0f / %.0f | %.0f | %.2f |\n", (long long)r.actors, r.view, r.traditionalMs,
                    r.actorMs, r.impostorMs, r.traditionalMs / r.actorMs, r.traditionalMs / r.impostorMs, r.posed, r.posedWithImpostors,
                    r.impostors, r.stepMs);
    if (!o.csv.empty()) {
        std::ofstream csv(o.csv);
        csv << "actors,camera,traditional_ms,actor_ms,actor_impostor_ms,posed,posed_with_impostors,impostors,step_ms\n";
        for (const Row& r : rows)
            csv << r.actors << ',' << r.view << ',' << r.traditionalMs << ',' << r.actorMs << ',' << r.impostorMs << ',' << r.posed << ','
                << r.posedWithImpostors << ',' << r.impostors << ',' << r.stepMs << '\n';
    }
    try {
        for (const View& view : kViews) {
            std::fprintf(stderr, "bench_town: end to end, %lld actors at 1280 x 720, %s camera, %d frames...\n", (long long)o.actors.front(),
                         view.name, o.drawFrames);
            double appCull = 0, draw = 0;
            const double fps = endToEndFps(o, o.actors.front(), view, &appCull, &draw);
            std::printf("\nEnd to end, headless 1280 x 720, %lld actors, %s camera (actor processing with impostors, one thread): "
                        "%.1f fps (APP+CULL %.2f ms, DRAW with impostors %.1f ms per frame)\n",
                        (long long)o.actors.front(), view.name, fps, appCull, draw);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_town: end-to-end run failed: %s\n", e.what());
        return 1;
    }
    return 0;
}
