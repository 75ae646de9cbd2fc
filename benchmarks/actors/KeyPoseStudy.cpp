#include "KeyPoseStudy.h"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <istream>
#include <map>
#include <numbers>
#include <numeric>
#include <ostream>
#include <random>
#include <stdexcept>

#include "throng/research/KeyPoseExactSelection.h"

namespace throng::bench {
namespace {

using Clock = std::chrono::steady_clock;

double microsecondsSince(Clock::time_point start) {
    return std::chrono::duration<double, std::micro>(Clock::now() - start).count();
}

std::string trimmed(const std::string& s) {
    const auto first = s.find_first_not_of(" \t\r");
    if (first == std::string::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

template <class T>
T wholeField(const std::string& text, const std::string& what, const std::string& where) {
    T value{};
    const std::string t = trimmed(text);
    const auto [end, error] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (t.empty() || error != std::errc() || end != t.data() + t.size())
        throw std::runtime_error(where + ": " + what + " '" + t + "' is not a whole number in range");
    return value;
}

}  // namespace

KeyPoseFrames randomKeyPoseFrames(std::uint32_t frames, std::uint32_t characters, std::uint32_t poses, double sd,
                                  double nextPose, bool intermittent, std::uint32_t firstSeed) {
    if (poses < 2) throw std::invalid_argument("randomKeyPoseFrames: at least 2 key-poses are needed");
    KeyPoseFrames out;
    for (std::uint32_t f = 0; f < frames; ++f) {
        std::mt19937 rng(firstSeed + f);
        const auto unit = [&] { return (static_cast<double>(rng()) + 0.5) / 4294967296.0; };  // in (0, 1)
        const auto normalPose = [&] {
            const double u1 = unit(), u2 = unit();
            const double z = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
            const double x = std::round((poses - 1) / 2.0 + z * sd);
            return static_cast<std::uint32_t>(std::clamp(x, 0.0, static_cast<double>(poses - 1)));
        };
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> count;
        for (std::uint32_t c = 0; c < characters; ++c) {
            const std::uint32_t a = normalPose();
            std::uint32_t b = a;
            if (!intermittent) {
                if (unit() < nextPose) b = (a + 1) % poses;
                else
                    while (b == a) b = normalPose();
            }
            ++count[{std::min(a, b), std::max(a, b)}];
        }
        std::vector<KeyPoseDemand> demand;
        for (const auto& [pair, n] : count) demand.push_back({pair.first, pair.second, n});
        out.push_back(std::move(demand));
    }
    return out;
}

KeyPoseFrames readKeyPoseDemandsCsv(std::istream& in, const std::string& name) {
    std::string line;
    std::size_t number = 0;
    bool header = false;
    std::map<std::uint64_t, std::vector<KeyPoseDemand>> byFrame;
    while (std::getline(in, line)) {
        ++number;
        const std::string where = name + ":" + std::to_string(number);
        const std::string t = trimmed(line);
        if (t.empty()) continue;
        if (!header) {
            std::string squeezed;
            for (const char c : t)
                if (c != ' ' && c != '\t') squeezed += c;
            if (squeezed != "frame,a,b,actors")
                throw std::runtime_error(where + ": the header must be 'frame,a,b,actors', got '" + t + "'");
            header = true;
            continue;
        }
        std::vector<std::string> fields(1);
        for (const char c : t) {
            if (c == ',') fields.emplace_back();
            else fields.back() += c;
        }
        if (fields.size() != 4)
            throw std::runtime_error(where + ": expected 4 fields (frame,a,b,actors), got " + std::to_string(fields.size()));
        KeyPoseDemand d;
        const auto frame = wholeField<std::uint64_t>(fields[0], "frame", where);
        d.a = wholeField<std::uint32_t>(fields[1], "pose a", where);
        d.b = wholeField<std::uint32_t>(fields[2], "pose b", where);
        d.actors = wholeField<std::uint32_t>(fields[3], "actors", where);
        byFrame[frame].push_back(d);
    }
    if (in.bad()) throw std::runtime_error(name + ": read error");
    if (!header) throw std::runtime_error(name + ": empty (expected the header 'frame,a,b,actors')");
    KeyPoseFrames out;
    for (auto& [frame, demand] : byFrame) out.push_back(std::move(demand));
    return out;
}

std::uint32_t keyPoseCount(const KeyPoseFrames& frames, std::uint32_t given) {
    constexpr std::uint32_t kMostPoses = 1u << 24;
    if (given > kMostPoses)
        throw std::invalid_argument("key-poses: " + std::to_string(given) + ", at most " + std::to_string(kMostPoses) + " are supported");
    const std::uint32_t limit = given > 0 ? given : kMostPoses;
    std::uint32_t most = 0;
    for (std::size_t f = 0; f < frames.size(); ++f)
        for (const KeyPoseDemand& d : frames[f]) {
            const std::uint32_t p = std::max(d.a, d.b);
            if (p >= limit)
                throw std::invalid_argument("key-poses: frame " + std::to_string(f) + " names pose " + std::to_string(p) +
                                            (given > 0 ? " but there are only " + std::to_string(given)
                                                       : ", beyond the " + std::to_string(kMostPoses) + " key-poses supported"));
            most = std::max(most, p + 1);
        }
    return given > 0 ? given : most;
}

std::vector<KeyPoseStudyRow> studyKeyPoseSelection(const KeyPoseFrames& frames, std::span<const std::uint32_t> capacities,
                                                   const KeyPoseStudyOptions& options) {
    const std::uint32_t poseCount = keyPoseCount(frames, options.poseCount);
    KeyPoseExactSettings exactSettings;
    exactSettings.timeLimitSeconds = options.exactTimeLimit;
    exactSettings.poseCount = poseCount;
    const std::uint32_t repeats = std::max<std::uint32_t>(1, options.greedyRepeats);
    std::vector<KeyPoseStudyRow> rows;
    for (const std::uint32_t capacity : capacities) {
        KeyPoseStudyRow row;
        row.capacity = capacity;
        row.frames = frames.size();
        double greedySum = 0, exactSum = 0, actorsSum = 0, firstSum = 0, randomSum = 0, boundSum = 0;
        double greedyMicros = 0, exactMicros = 0;
        std::mt19937 rng(options.randomSeed + capacity);
        std::vector<std::uint32_t> all(poseCount);
        std::iota(all.begin(), all.end(), 0u);
        const std::uint32_t n = std::min(capacity, poseCount);
        const std::vector<std::uint32_t> first(all.begin(), all.begin() + n);
        for (const auto& demand : frames) {
            for (const KeyPoseDemand& d : demand) actorsSum += d.actors;
            // Greedy, timed over several runs (it takes microseconds).
            std::vector<std::uint32_t> greedy;
            const Clock::time_point g0 = Clock::now();
            for (std::uint32_t r = 0; r < repeats; ++r) greedy = selectKeyPosesGreedy(demand, capacity);
            greedyMicros += microsecondsSince(g0) / repeats;
            const double greedyServed = static_cast<double>(actorsServed(demand, greedy));
            const KeyPoseExactResult exact = selectKeyPosesExact(demand, capacity, {}, exactSettings);
            exactMicros += exact.seconds * 1e6;
            row.exactMicrosecondsMax = std::max(row.exactMicrosecondsMax, exact.seconds * 1e6);
            if (!exact.optimal()) ++row.exactUnproven;
            boundSum += static_cast<double>(exact.bound);
            const double exactServed = static_cast<double>(exact.served);
            if (greedyServed < exactServed) ++row.greedyBelowExact;
            if (exactServed > 0) row.worstGreedyOverExact = std::min(row.worstGreedyOverExact, greedyServed / exactServed);
            greedySum += greedyServed;
            exactSum += exactServed;
            firstSum += static_cast<double>(actorsServed(demand, first));
            std::shuffle(all.begin(), all.end(), rng);
            randomSum += static_cast<double>(actorsServed(demand, std::span<const std::uint32_t>(all.data(), n)));
        }
        const double f = frames.empty() ? 1.0 : static_cast<double>(frames.size());
        row.actors = actorsSum / f;
        row.greedy = greedySum / f;
        row.exact = exactSum / f;
        row.firstN = firstSum / f;
        row.randomN = randomSum / f;
        row.exactBound = boundSum / f;
        row.greedyOverExact = exactSum > 0 ? greedySum / exactSum : 1.0;
        row.greedyMicroseconds = greedyMicros / f;
        row.exactMicrosecondsMean = exactMicros / f;
        rows.push_back(row);
    }
    return rows;
}

void writeKeyPoseStudyCsv(std::ostream& out, std::span<const KeyPoseStudyRow> rows) {
    out << "capacity,frames,actors,greedy,exact,first_n,random_n,greedy_over_exact,worst_greedy_over_exact,"
           "frames_greedy_below_exact,frames_exact_unproven,exact_bound,greedy_us,exact_us_mean,exact_us_max\n";
    for (const KeyPoseStudyRow& r : rows)
        out << r.capacity << ',' << r.frames << ',' << r.actors << ',' << r.greedy << ',' << r.exact << ',' << r.firstN << ','
            << r.randomN << ',' << r.greedyOverExact << ',' << r.worstGreedyOverExact << ',' << r.greedyBelowExact << ','
            << r.exactUnproven << ',' << r.exactBound << ',' << r.greedyMicroseconds << ',' << r.exactMicrosecondsMean << ','
            << r.exactMicrosecondsMax << '\n';
}

}  // namespace throng::bench
