#pragma once
// The ladder of a frame-budget allocator: settings of the knobs that trade image error for frame
// time (LOD scale, impostor distance, key-pose distance, morph budget, render scale, town LOD scale), ordered from the most
// accurate rung to the cheapest, each with the image error and the APP+CULL+DRAW time measured for
// it (bench_budget). Stored as the common accuracy CSV (AccuracyCsv.h): knob "frame budget rung",
// the settings in the value, one line per metric; the rung's error is its "pixels_off_8" line.

#include <string>
#include <vector>

namespace throng::sim {

/// The knob settings of one rung (what throng-town's --lod-scale, --impostor-distance,
/// --morph-budget and the scene's key-pose distance set once, a rung sets per frame).
struct BudgetSettings {
    double lodScale = 1.0;          ///< multiplies every LOD distance (> 0)
    double impostorDistance = 0.0;  ///< metres beyond which actors are impostors (0: none)
    double keyPoseDistance = 0.0;   ///< metres beyond which actors come from key-pose caches (0: none)
    int morphBudget = 2;            ///< new morphed impostor cells per atlas and frame (0: none)
    /// Dynamic resolution: the frame drawn at this fraction of the output's width and height, scaled
    /// up (0 < scale <= 1). Optional in a rung's value ("render-scale=0.5"), 1 when absent.
    double renderScale = 1.0;
    /// The town's LOD scale apart from the actors' (Simulation::setTownLodScale), used where
    /// the scene built the town's levels. Optional ("town-lod-scale=2"); 0 when absent: the scene's.
    double townLodScale = 0.0;
};

/// One rung: its settings and what they were measured to cost and err.
struct BudgetRung {
    BudgetSettings settings;  ///< the knobs this rung sets
    double error = 0.0;   ///< share of pixels off by more than 8/255 against every approximation off
    double psnr = 0.0;    ///< dB against every approximation off (0 when the ladder has none)
    double ssim = 0.0;    ///< against every approximation off (0 when the ladder has none)
    double ms = 0.0;      ///< mean APP+CULL+DRAW measured (> 0)
};

/// The knob name of ladder rows in the accuracy CSV.
inline constexpr const char* kBudgetRungKnob = "frame budget rung";

/// The value column of a rung: "lod-scale=1 impostor-distance=40 key-pose-distance=20 morph-budget=2",
/// followed by " render-scale=S" when S is below 1 and " town-lod-scale=T" when T is set.
std::string budgetRungValue(const BudgetSettings& settings);
/// Parses budgetRungValue's text (every key once, in any order; render-scale and town-lod-scale may be left out).
/// Throws std::invalid_argument naming the key or value at fault.
BudgetSettings parseBudgetRungValue(const std::string& value);

/// Reads a ladder from an accuracy CSV: its "frame budget rung" rows in file order (the most
/// accurate first). Throws std::runtime_error naming the file and line of the fault: an unreadable
/// file or header, a bad value, a rung without a pixels_off_8 line, no rung at all, or a rung whose
/// error is below the one before it (the ladder must go from accurate to cheap).
std::vector<BudgetRung> readBudgetLadder(const std::string& path);

}  // namespace throng::sim
