// The frame-budget ladder: its rungs' value text and reading them from the common accuracy CSV.

#include "throng/sim/BudgetLadder.h"

#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>
#include <stdexcept>

#include "throng/sim/AccuracyCsv.h"

namespace throng::sim {

namespace {

std::string number(double v) {
    std::ostringstream s;
    s.precision(6);
    s << v;
    return s.str();
}

double parseNumber(const std::string& key, const std::string& text) {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(v))
        throw std::invalid_argument(key + "='" + text + "' is not a finite number");
    return v;
}

}  // namespace

std::string budgetRungValue(const BudgetSettings& s) {
    return "lod-scale=" + number(s.lodScale) + " impostor-distance=" + number(s.impostorDistance) +
           " key-pose-distance=" + number(s.keyPoseDistance) + " morph-budget=" + std::to_string(s.morphBudget) +
           (s.renderScale < 1.0 ? " render-scale=" + number(s.renderScale) : std::string()) +
           (s.townLodScale > 0.0 ? " town-lod-scale=" + number(s.townLodScale) : std::string());
}

BudgetSettings parseBudgetRungValue(const std::string& value) {
    BudgetSettings s;
    std::map<std::string, bool> seen{{"lod-scale", false}, {"impostor-distance", false}, {"key-pose-distance", false}, {"morph-budget", false},
                                     {"render-scale", false}, {"town-lod-scale", false}};
    std::istringstream in(value);
    std::string item;
    while (in >> item) {
        const auto eq = item.find('=');
        if (eq == std::string::npos) throw std::invalid_argument("'" + item + "' is not key=value");
        const std::string key = item.substr(0, eq), text = item.substr(eq + 1);
        const auto it = seen.find(key);
        if (it == seen.end())
            throw std::invalid_argument("unknown key '" + key + "' (expected lod-scale, impostor-distance, key-pose-distance, morph-budget, render-scale, town-lod-scale)");
        if (it->second) throw std::invalid_argument("key '" + key + "' given twice");
        it->second = true;
        const double v = parseNumber(key, text);
        if (key == "lod-scale") {
            if (v <= 0) throw std::invalid_argument("lod-scale=" + text + " must be > 0");
            s.lodScale = v;
        } else if (key == "impostor-distance" || key == "key-pose-distance") {
            if (v < 0) throw std::invalid_argument(key + "=" + text + " must be >= 0");
            (key == "impostor-distance" ? s.impostorDistance : s.keyPoseDistance) = v;
        } else if (key == "town-lod-scale") {
            if (v <= 0) throw std::invalid_argument("town-lod-scale=" + text + " must be > 0");
            s.townLodScale = v;
        } else if (key == "render-scale") {
            if (v <= 0 || v > 1) throw std::invalid_argument("render-scale=" + text + " must be above 0 and at most 1");
            s.renderScale = v;
        } else {
            if (v < 0 || v != std::floor(v) || v > 100000) throw std::invalid_argument("morph-budget=" + text + " must be a whole number 0..100000");
            s.morphBudget = int(v);
        }
    }
    for (const auto& [key, given] : seen)
        if (!given && key != "render-scale" && key != "town-lod-scale") throw std::invalid_argument("key '" + key + "' missing");
    return s;
}

std::vector<BudgetRung> readBudgetLadder(const std::string& path) {
    const std::vector<AccuracyRow> rows = readAccuracyCsv(path);
    std::vector<BudgetRung> ladder;
    std::vector<std::string> values;
    std::vector<int> lines;
    std::vector<bool> hasError;
    for (const AccuracyRow& r : rows) {
        if (r.knob != kBudgetRungKnob) continue;
        const std::string where = r.file + ":" + std::to_string(r.line);
        std::size_t i = 0;
        while (i < values.size() && values[i] != r.value) ++i;
        if (i == values.size()) {
            BudgetRung rung;
            try {
                rung.settings = parseBudgetRungValue(r.value);
            } catch (const std::invalid_argument& e) {
                throw std::runtime_error(where + ": rung '" + r.value + "': " + e.what());
            }
            if (!(r.ms > 0)) throw std::runtime_error(where + ": rung '" + r.value + "': ms must be > 0");
            rung.ms = r.ms;
            ladder.push_back(rung);
            values.push_back(r.value);
            lines.push_back(r.line);
            hasError.push_back(false);
        } else if (i + 1 != values.size()) {
            throw std::runtime_error(where + ": rung '" + r.value + "' again after other rungs (a rung's lines go together)");
        }
        BudgetRung& rung = ladder[i];
        if (r.metric.name == "pixels_off_8") rung.error = r.metric.value, hasError[i] = true;
        else if (r.metric.name == "psnr") rung.psnr = r.metric.value;
        else if (r.metric.name == "ssim") rung.ssim = r.metric.value;
    }
    if (ladder.empty()) throw std::runtime_error(path + ": no '" + std::string(kBudgetRungKnob) + "' rows (not a frame-budget ladder)");
    for (std::size_t i = 0; i < ladder.size(); ++i) {
        const std::string where = path + ":" + std::to_string(lines[i]);
        if (!hasError[i]) throw std::runtime_error(where + ": rung '" + values[i] + "' has no pixels_off_8 line");
        if (i > 0 && ladder[i].error < ladder[i - 1].error)
            throw std::runtime_error(where + ": rung '" + values[i] + "' errs less than the rung before it (the ladder goes from accurate to cheap)");
    }
    return ladder;
}

}  // namespace throng::sim
