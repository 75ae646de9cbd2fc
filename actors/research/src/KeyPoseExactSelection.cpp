#include "throng/research/KeyPoseExactSelection.h"

#include <glpk.h>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <unordered_set>

#include "throng/actors/KeyPoseRows.h"

namespace throng {
namespace {

using Clock = std::chrono::steady_clock;

// One demand per distinct pose set, poses ordered (lo <= hi).
struct Pair {
    std::uint32_t lo = 0, hi = 0;
    std::uint64_t actors = 0;
};

// Serialises solves when GLPK keeps its environment in globals rather than per thread.
std::mutex& glpkLock() {
    static std::mutex lock;
    return lock;
}

bool glpkIsThreadLocal() {
    static const bool tls = glp_config("TLS") != nullptr;
    return tls;
}

// Silences GLPK's terminal for the solve and restores the caller's setting after it.
class QuietGlpk {
public:
    QuietGlpk() : previous_(glp_term_out(GLP_OFF)) {}
    ~QuietGlpk() { glp_term_out(previous_); }
    QuietGlpk(const QuietGlpk&) = delete;
    QuietGlpk& operator=(const QuietGlpk&) = delete;

private:
    int previous_;
};

struct ProbDeleter {
    void operator()(glp_prob* p) const { glp_delete_prob(p); }
};

// What the branch-and-bound callback reads and writes.
struct Search {
    std::vector<double> start;  // the greedy selection as column values (1-based), offered once
    bool offered = false;
    double bestOpenBound = HUGE_VAL;  // smallest "best bound of the open nodes" seen: a valid upper bound
};

void searchCallback(glp_tree* tree, void* info) {
    Search& s = *static_cast<Search*>(info);
    if (glp_ios_reason(tree) == GLP_IHEUR && !s.offered) {
        s.offered = true;  // the search starts from the greedy selection, so it never ends below it
        glp_ios_heur_sol(tree, s.start.data());
    }
    if (const int node = glp_ios_best_node(tree); node != 0) s.bestOpenBound = std::min(s.bestOpenBound, glp_ios_node_bound(tree, node));
}

void checkPose(std::uint32_t pose, std::uint32_t poseCount, const std::string& where) {
    if (pose == KeyPoseRows::kNone)
        throw std::invalid_argument("selectKeyPosesExact: " + where + " names pose " + std::to_string(pose) +
                                    " (KeyPoseRows::kNone, no pose)");
    if (poseCount > 0 && pose >= poseCount)
        throw std::invalid_argument("selectKeyPosesExact: " + where + " names pose " + std::to_string(pose) + " but there are only " +
                                    std::to_string(poseCount) + " poses");
}

int milliseconds(double seconds) {
    const double ms = std::ceil(seconds * 1000.0);
    if (!(ms < static_cast<double>(INT_MAX))) return INT_MAX;  // infinity: GLPK's "no limit"
    return std::max(1, static_cast<int>(ms));
}

}  // namespace

KeyPoseExactResult selectKeyPosesExact(std::span<const KeyPoseDemand> demand, std::uint32_t capacity,
                                       std::span<const std::uint32_t> resident, const KeyPoseExactSettings& settings) {
    const Clock::time_point start = Clock::now();
    if (!(settings.timeLimitSeconds > 0.0))
        throw std::invalid_argument("selectKeyPosesExact: timeLimitSeconds " + std::to_string(settings.timeLimitSeconds) +
                                    " must be positive (infinity: no limit)");
    if (settings.maxDemands == 0) throw std::invalid_argument("selectKeyPosesExact: maxDemands must be at least 1");
    for (std::size_t i = 0; i < demand.size(); ++i) {
        checkPose(demand[i].a, settings.poseCount, "demand " + std::to_string(i));
        checkPose(demand[i].b, settings.poseCount, "demand " + std::to_string(i));
    }
    std::unordered_set<std::uint32_t> isResident;
    for (std::size_t i = 0; i < resident.size(); ++i) {
        checkPose(resident[i], settings.poseCount, "resident entry " + std::to_string(i));
        if (!isResident.insert(resident[i]).second)
            throw std::invalid_argument("selectKeyPosesExact: resident pose " + std::to_string(resident[i]) + " is listed twice");
    }

    // Distinct pose sets with their actors; the poses they name are the candidates.
    std::vector<Pair> pairs;
    for (const KeyPoseDemand& d : demand)
        if (d.actors > 0) pairs.push_back({std::min(d.a, d.b), std::max(d.a, d.b), d.actors});
    std::sort(pairs.begin(), pairs.end(), [](const Pair& p, const Pair& q) { return p.lo != q.lo ? p.lo < q.lo : p.hi < q.hi; });
    std::size_t kept = 0;
    for (const Pair& p : pairs) {
        if (kept > 0 && pairs[kept - 1].lo == p.lo && pairs[kept - 1].hi == p.hi) pairs[kept - 1].actors += p.actors;
        else pairs[kept++] = p;
    }
    pairs.resize(kept);
    std::uint64_t total = 0;
    std::vector<std::uint32_t> candidates;
    for (const Pair& p : pairs) {
        total += p.actors;
        candidates.push_back(p.lo);
        candidates.push_back(p.hi);
    }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());

    KeyPoseExactResult result;
    // The result holds exactly the poses of the demands `chosen` serves.
    const auto finish = [&](const std::unordered_set<std::uint32_t>& chosen) {
        std::unordered_set<std::uint32_t> used;
        result.served = 0;
        for (const Pair& p : pairs)
            if (chosen.count(p.lo) && chosen.count(p.hi)) {
                result.served += p.actors;
                used.insert(p.lo);
                used.insert(p.hi);
            }
        result.poses.assign(used.begin(), used.end());
        std::sort(result.poses.begin(), result.poses.end());
        result.updates = 0;
        for (const std::uint32_t p : result.poses) result.updates += isResident.count(p) ? 0u : 1u;
        result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
        return result;
    };
    const auto greedy = [&] {
        const std::vector<std::uint32_t> g = selectKeyPosesGreedy(demand, capacity, resident);
        return std::unordered_set<std::uint32_t>(g.begin(), g.end());
    };

    // Trivial cases: nothing fits, or everything does.
    if (capacity == 0) {
        result.bound = 0;
        return finish({});
    }
    if (candidates.size() <= capacity) {
        result.bound = total;
        return finish(std::unordered_set<std::uint32_t>(candidates.begin(), candidates.end()));
    }
    if (pairs.size() > settings.maxDemands) {
        result.status = KeyPoseExactStatus::SizeLimit;
        result.bound = total;
        return finish(greedy());
    }

    // Objective W * actors served - poses not resident: with W above the most non-resident poses a
    // selection can hold, one more actor always outweighs any number of updates, so the preference
    // for resident poses only breaks ties. All coefficients are integers (GLPK then rounds bounds).
    constexpr double kExact = 9007199254740992.0;  // 2^53: doubles hold integers exactly below it
    if (static_cast<double>(total) >= kExact)
        throw std::invalid_argument("selectKeyPosesExact: " + std::to_string(total) + " actors in all is too many to solve exactly");
    std::size_t nonResident = 0;
    for (const std::uint32_t p : candidates) nonResident += isResident.count(p) ? 0u : 1u;
    double weight = static_cast<double>(std::min<std::size_t>(capacity, nonResident) + 1);
    bool preferResident = nonResident > 0;
    if (weight * static_cast<double>(total) >= kExact) weight = 1.0, preferResident = false;

    std::unique_lock<std::mutex> lock(glpkLock(), std::defer_lock);
    if (!glpkIsThreadLocal()) lock.lock();
    const QuietGlpk quiet;
    const std::unique_ptr<glp_prob, ProbDeleter> lp(glp_create_prob());
    glp_set_obj_dir(lp.get(), GLP_MAX);
    const int poses = static_cast<int>(candidates.size());
    const int demands = static_cast<int>(pairs.size());
    // Columns 1..poses: y (pose chosen); poses+1..poses+demands: x (demand served).
    glp_add_cols(lp.get(), poses + demands);
    const auto column = [&](std::uint32_t pose) {
        return 1 + static_cast<int>(std::lower_bound(candidates.begin(), candidates.end(), pose) - candidates.begin());
    };
    for (int j = 1; j <= poses; ++j) {
        glp_set_col_kind(lp.get(), j, GLP_BV);
        glp_set_obj_coef(lp.get(), j, preferResident && !isResident.count(candidates[static_cast<std::size_t>(j - 1)]) ? -1.0 : 0.0);
    }
    for (int d = 0; d < demands; ++d) {
        glp_set_col_kind(lp.get(), poses + 1 + d, GLP_BV);
        glp_set_obj_coef(lp.get(), poses + 1 + d, weight * static_cast<double>(pairs[static_cast<std::size_t>(d)].actors));
    }
    // Row 1: sum y <= capacity; then x_d - y_p <= 0 for each pose p of each demand d.
    std::vector<int> ia{0}, ja{0};
    std::vector<double> ar{0.0};
    const auto entry = [&](int row, int col, double value) {
        ia.push_back(row);
        ja.push_back(col);
        ar.push_back(value);
    };
    int rows = 1;
    for (int j = 1; j <= poses; ++j) entry(1, j, 1.0);
    for (int d = 0; d < demands; ++d) {
        const Pair& p = pairs[static_cast<std::size_t>(d)];
        const int posesOfDemand = p.lo == p.hi ? 1 : 2;  // an intermittent demand needs one pose
        for (int k = 0; k < posesOfDemand; ++k) {
            ++rows;
            entry(rows, poses + 1 + d, 1.0);
            entry(rows, column(k == 0 ? p.lo : p.hi), -1.0);
        }
    }
    glp_add_rows(lp.get(), rows);
    glp_set_row_bnds(lp.get(), 1, GLP_UP, 0.0, static_cast<double>(capacity));
    for (int r = 2; r <= rows; ++r) glp_set_row_bnds(lp.get(), r, GLP_UP, 0.0, 0.0);
    glp_load_matrix(lp.get(), static_cast<int>(ia.size()) - 1, ia.data(), ja.data(), ar.data());

    const auto servedBound = [&](double objectiveBound) {
        // served * W - updates <= bound and updates < W, so served <= (bound + W - 1) / W.
        const double b = std::floor((objectiveBound + weight - 1.0) / weight + 1e-6);
        return b <= 0.0 ? std::uint64_t{0} : std::min(total, static_cast<std::uint64_t>(b));
    };
    const auto remaining = [&] {
        return settings.timeLimitSeconds - std::chrono::duration<double>(Clock::now() - start).count();
    };

    // The LP relaxation first (the branch and bound without presolve needs its basis).
    glp_smcp simplex;
    glp_init_smcp(&simplex);
    simplex.msg_lev = GLP_MSG_OFF;
    simplex.tm_lim = milliseconds(remaining());
    const int lpCode = glp_simplex(lp.get(), &simplex);
    if (lpCode == GLP_ETMLIM) {
        result.status = KeyPoseExactStatus::TimeLimit;
        result.bound = total;
        return finish(greedy());
    }
    if (lpCode != 0 || glp_get_status(lp.get()) != GLP_OPT)
        throw std::runtime_error("selectKeyPosesExact: GLPK's simplex failed on the relaxation (code " + std::to_string(lpCode) +
                                 ", status " + std::to_string(glp_get_status(lp.get())) + ")");

    // Branch and bound, started from the greedy selection. No presolve: the heuristic solution is
    // given in the columns of this problem.
    const std::unordered_set<std::uint32_t> fallback = greedy();
    Search search;
    search.bestOpenBound = glp_get_obj_val(lp.get());
    search.start.assign(static_cast<std::size_t>(poses + demands + 1), 0.0);
    for (const std::uint32_t p : fallback) search.start[static_cast<std::size_t>(column(p))] = 1.0;
    for (int d = 0; d < demands; ++d) {
        const Pair& p = pairs[static_cast<std::size_t>(d)];
        search.start[static_cast<std::size_t>(poses + 1 + d)] = fallback.count(p.lo) && fallback.count(p.hi) ? 1.0 : 0.0;
    }
    glp_iocp mip;
    glp_init_iocp(&mip);
    mip.msg_lev = GLP_MSG_OFF;
    mip.presolve = GLP_OFF;
    mip.tm_lim = milliseconds(std::max(remaining(), 0.0));
    mip.cb_func = searchCallback;
    mip.cb_info = &search;
    const int mipCode = glp_intopt(lp.get(), &mip);
    const int mipStatus = glp_mip_status(lp.get());
    if (mipCode == 0 && mipStatus == GLP_OPT) {
        result.status = KeyPoseExactStatus::Optimal;
    } else if (mipCode == GLP_ETMLIM) {
        result.status = KeyPoseExactStatus::TimeLimit;
    } else {
        throw std::runtime_error("selectKeyPosesExact: GLPK's branch and bound failed (code " + std::to_string(mipCode) + ", status " +
                                 std::to_string(mipStatus) + ")");
    }
    std::unordered_set<std::uint32_t> chosen;
    if (mipStatus == GLP_OPT || mipStatus == GLP_FEAS) {
        for (int j = 1; j <= poses; ++j)
            if (glp_mip_col_val(lp.get(), j) > 0.5) chosen.insert(candidates[static_cast<std::size_t>(j - 1)]);
    } else {
        chosen = fallback;  // stopped before any solution was accepted
    }
    finish(chosen);
    if (result.optimal()) {
        result.bound = result.served;
    } else {
        const double incumbent = mipStatus == GLP_FEAS ? glp_mip_obj_val(lp.get()) : -HUGE_VAL;
        result.bound = std::max(result.served, servedBound(std::max(incumbent, search.bestOpenBound)));
    }
    return result;
}

}  // namespace throng
