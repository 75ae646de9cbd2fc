#pragma once
// The optimal key-poses for a fixed-size cache (seed 004 §4.1): the set-union knapsack problem as
// an integer program, solved by GLPK's branch and bound. It is what the greedy selection of §4.2 is
// measured against (seed 004 Figure 7), and may serve small frames directly under a time limit.
//
// Threads: GLPK keeps its state per thread when built with thread-local storage (Debian's 5.0 is;
// glp_config("TLS")), so solves in different threads run in parallel; a GLPK built without it is
// not thread-safe, and then every solve takes one process-wide lock. GLPK's terminal output is
// switched off for the solve.

#include <cstdint>
#include <span>
#include <vector>

#include "throng/actors/KeyPoseSelection.h"

namespace throng {

/// Limits of an exact selection.
struct KeyPoseExactSettings {
    /// Wall-clock budget of the solver (seconds, > 0; infinity: none). When it runs out, the best
    /// selection found so far is returned (never worse than the greedy one) and not called optimal.
    double timeLimitSeconds = 10.0;
    /// Distinct demands (pose pairs with actors) above which the solver is not started at all and
    /// the greedy selection is returned instead (> 0).
    std::size_t maxDemands = 20000;
    /// When > 0, every pose named (in demands and in `resident`) must be below it.
    std::uint32_t poseCount = 0;
};

/// Why an exact selection stopped.
enum class KeyPoseExactStatus : std::uint8_t {
    Optimal,    ///< proven optimal (solved, or trivially: everything fits, or capacity 0)
    TimeLimit,  ///< the time limit stopped the search: best found, not proven
    SizeLimit,  ///< more demands than maxDemands: the greedy selection, not searched
};

/// The outcome of an exact selection.
struct KeyPoseExactResult {
    std::vector<std::uint32_t> poses;  ///< chosen poses, ascending: exactly those of the served demands
    std::uint64_t served = 0;          ///< actors whose every pose is chosen
    /// Proven upper bound on the actors any selection serves (== served when optimal; from the
    /// search's best open node when stopped by time; all demanded actors when not searched).
    std::uint64_t bound = 0;
    std::uint32_t updates = 0;         ///< chosen poses not in `resident` (rows to skin)
    KeyPoseExactStatus status = KeyPoseExactStatus::Optimal;  ///< why it stopped
    double seconds = 0.0;              ///< wall-clock time of the whole call
    /// Whether optimality was proven.
    bool optimal() const { return status == KeyPoseExactStatus::Optimal; }
};

/// Chooses at most `capacity` poses serving the most actors (an actor is served when every pose of
/// its demand is chosen): maximise sum(actors_d x_d) subject to x_d <= y_a, x_d <= y_b,
/// sum(y) <= capacity, x, y binary. Among selections serving equally many it prefers the one with
/// the fewest poses not in `resident` (fewest cache updates); this preference never costs a served
/// actor. Capacity 0 is allowed (nothing chosen). Demands of no actors are ignored; the same pair
/// may appear several times (in either order). Throws std::invalid_argument naming the problem for
/// a bad setting, a pose equal to KeyPoseRows::kNone or not below settings.poseCount, or a pose
/// listed twice in `resident`; std::runtime_error if GLPK fails.
KeyPoseExactResult selectKeyPosesExact(std::span<const KeyPoseDemand> demand, std::uint32_t capacity,
                                       std::span<const std::uint32_t> resident = {},
                                       const KeyPoseExactSettings& settings = {});

}  // namespace throng
