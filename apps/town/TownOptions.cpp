#include "TownOptions.h"

#include <stdexcept>
#include <string>

#include "throng/support/CommandLine.h"
#include "throng/support/GlOption.h"
#include "throng/support/SceneOptions.h"
#include "throng/support/Validators.h"

namespace throng::town {
namespace {

constexpr const char* kName = "throng-town";

// Declares every option of throng-town on `cl`, bound to `o`.
void declare(support::CommandLine& cl, TownOptions& o) {
    using namespace support;
    CLI::App& app = cl.app();
    declareSceneOptions(app, o.scene, o.actors, o.seed);
    app.add_option("--frames", o.frames, "frames to run headless; in a window, quit after N")
        ->type_name("N")
        ->check(wholeNumber(1, 100'000'000));
    app.add_option("--out", o.out, "frames, stats.csv and summary.json go here")->type_name("DIR")->check(folderToWrite());
    app.add_option("--width", o.width, "image width in pixels")->type_name("W")->check(wholeNumber(16, 8192));
    app.add_option("--height", o.height, "image height in pixels")->type_name("H")->check(wholeNumber(16, 8192));
    app.add_flag("--headless", o.headless, "never open a window (the default when there is no display)");
    support::declareGlOption(app, o.gl);
    app.add_option("--processing", o.processing, "how the scene is processed")
        ->type_name("MODE")
        ->check(oneOf({"actor", "traditional"}));
    app.add_option("--every", o.every, "headless: a PNG frame every K frames (0: none)")
        ->type_name("K")
        ->check(wholeNumber(0, 1'000'000));
    app.add_option("--threads", o.threads, "threads for the simulation step and the per-actor phases")
        ->type_name("N")
        ->check(wholeNumber(1, 256));
    app.add_option("--pipeline", o.pipeline, "DRAW of frame N overlaps the step, APP and CULL of frame N+1")
        ->type_name("on|off")
        ->check(oneOf({"on", "off"}))
        ->default_str("on");
    app.add_option("--occlusion", o.occlusion, "occlusion culling as the scene declares it (off: never)")
        ->type_name("on|off")
        ->check(oneOf({"on", "off"}))
        ->default_str("on");
    app.add_option("--key-pose-cache", o.keyPoseCache, "key-pose caches as the scene declares them (off: never)")
        ->type_name("on|off")
        ->check(oneOf({"on", "off"}))
        ->default_str("on");
    app.add_option("--looks", o.looks, "the looks the scene gives its characters (off: every actor as modelled)")
        ->type_name("on|off")
        ->check(oneOf({"on", "off"}))
        ->default_str("on");
    app.add_option("--faces", o.faces,
                   "the faces the scene declares: effects face (expressions), blink and phrase (spoken, captioned above near "
                   "speakers), each within its distance bands (off: none is made, every face neutral)")
        ->type_name("on|off")
        ->check(oneOf({"on", "off"}))
        ->default_str("on");
    app.add_option("--lod-scale", o.lodScale, "multiplies every LOD distance")
        ->type_name("X")
        ->check(positiveNumber())
        ->default_str("the scene's");
    app.add_option("--impostor-distance", o.impostorDistance,
                   "actors beyond D metres are drawn as impostors (0: never)")
        ->type_name("D")
        ->check(nonNegativeNumber())
        ->default_str("the scene's");
    app.add_option("--morph-budget", o.morphBudget, "new morphed impostor cells per template and frame (0: show the nearest stored key-frame)")
        ->type_name("N")
        ->check(wholeNumber(0, 100000))
        ->capture_default_str();
    app.add_option("--render-scale", o.renderScale,
                   "dynamic resolution: frames drawn at this fraction of --width and --height, scaled up")
        ->type_name("S")
        ->check(support::number(0.05, 1.0))
        ->capture_default_str();
    app.add_option("--morph", o.morph,
                   "where impostor key-frames are morphed: background (CPU, 4 px warp grid, another thread, shown a frame later), "
                   "grid (the same on the drawing thread), cpu (every pixel), gl")
        ->type_name("background|grid|cpu|gl")
        ->check(oneOf({"background", "grid", "cpu", "gl"}))
        ->capture_default_str();
    app.add_option("--cell-warp", o.cellWarp,
                   "how a dropped impostor key-frame is made, on the CPU or (--morph gl) the GL: proxy (warped through "
                   "the figure's surface), lines (Beier-Neely along the bones)")
        ->type_name("proxy|lines")
        ->check(oneOf({"proxy", "lines"}))
        ->capture_default_str();
    CLI::Option* budget = app.add_option("--frame-budget", o.frameBudget,
                   "each frame, choose the LOD scale, impostor distance, key-pose distance, morph budget, render scale and town LOD scale from the ladder "
                   "to keep APP+CULL+DRAW under MS milliseconds with the least image error")
        ->type_name("MS")
        ->check(positiveNumber())
        ->default_str("none");
    app.add_option("--frame-budget-ladder", o.frameBudgetLadder,
                   "--frame-budget's settings, most accurate first, with their measured error and time (bench_budget --ladder)")
        ->type_name("FILE")
        ->check(existingFile())
        ->capture_default_str();
    // The allocator sets these every frame: one or the other.
    for (const char* fixed : {"--lod-scale", "--impostor-distance", "--morph-budget", "--render-scale"}) budget->excludes(fixed);
    app.add_option("--rank-timeout", o.rankTimeout,
                   "under mpirun: seconds a rank waits for another in an exchange before the run stops, naming it")
        ->type_name("S")
        ->check(positiveNumber())
        ->capture_default_str();
    app.add_option("--gather", o.gather,
                   "under mpirun: the walkers the other ranks send rank 0 each step: view (those that can be seen or looked at) or all")
        ->check(oneOf({"view", "all"}))
        ->capture_default_str();
    app.add_flag("--pose-on-ranks", o.poseOnRanks,
                 "under mpirun: every rank culls and poses the walkers it steps and sends rank 0 what to draw, not the walkers "
                 "(actor processing, --gather view, no --vtk)");
    app.add_option("--vtk", o.vtk, "write crowd data for ParaView here: actors every K steps, town, trajectories, crowd.pvd")
        ->type_name("DIR")
        ->check(folderToWrite());
    app.add_option("--vtk-every", o.vtkEvery, "--vtk: an actors file every K simulation steps")
        ->type_name("K")
        ->check(wholeNumber(1, 100'000'000))
        ->capture_default_str();
    app.footer(
        "Under mpirun -np N (headless), each rank steps its share of the walkers' regions and rank 0 draws.\n"
        "In a window: mouse drag looks, W/A/S/D/Q/E move, Tab path/free camera, Space pause,\n"
        "+/- LOD scale, C shrink the culling pyramid (watch culling at work), O show the occlusion buffer,\n"
        "P processing, Esc quit.");
}

}  // namespace

std::string townUsage() { return support::CommandLine::hint(kName); }

TownOptions parseTownOptions(int argc, char** argv, const std::string& defaultScene, const std::string& defaultLadder) {
    TownOptions o;
    o.scene = defaultScene;
    o.frameBudgetLadder = defaultLadder;
    support::CommandLine::parseOrExitOnHelp(
        kName,
        "The town-crowd example: builds the world a scene file declares (a town, walkers on its\n"
        "navigation mesh, standing groups, a flock) and runs it: in a window when there is a\n"
        "display, headless otherwise (PNG frames, stats.csv, summary.json).",
        argc, argv, [&](support::CommandLine& cl) { declare(cl, o); },
        [&](support::CommandLine& cl) {
            o.framesGiven = cl.app().count("--frames") > 0;
            if (o.gl == "window" && o.headless) throw std::invalid_argument("--gl: 'window' contradicts --headless");
            // Ranks posing their own walkers send rank 0 only what can be seen, drawn as actor processing draws it.
            if (o.poseOnRanks && o.processing == "traditional")
                throw std::invalid_argument("--pose-on-ranks: traditional processing reads every actor's state before culling; use --processing actor");
            if (o.poseOnRanks && o.gather == "all")
                throw std::invalid_argument("--pose-on-ranks: ranks posing their own walkers send rank 0 none: --gather all contradicts it");
            if (o.poseOnRanks && !o.vtk.empty())
                throw std::invalid_argument("--pose-on-ranks: --vtk records every walker on rank 0, which then holds none of the other ranks'");
            if (o.poseOnRanks && o.gl == "window")
                throw std::invalid_argument("--pose-on-ranks: ranks posing their own walkers follow the camera path, headless; --gl window contradicts it");
            // CLI11 checks the values given; the default folder is checked too, before any work.
            std::string out = o.out;
            if (cl.app().count("--out") == 0)
                if (const std::string problem = support::folderToWrite()(out); !problem.empty())
                    throw std::invalid_argument("--out: " + problem + " (the default folder: choose another with --out DIR)");
        });
    return o;
}

}  // namespace throng::town
