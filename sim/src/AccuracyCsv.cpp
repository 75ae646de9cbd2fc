// The common accuracy CSV: writing with checks, reading with line and column in every error.

#include "throng/sim/AccuracyCsv.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>

namespace throng::sim {

namespace {

constexpr int kFields = 13;

// A field as CSV: quoted when it holds a comma, a quote or a line break.
std::string field(const std::string& s) {
    if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) {
        if (c == '"') q += '"';
        q += c;
    }
    return q + '"';
}

std::string number(double v) {
    std::ostringstream s;
    s.precision(9);
    s << v;
    return s.str();
}

// Splits one CSV line (RFC 4180 quoting; no line breaks inside fields).
std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> out(1);
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
        const char c = line[i];
        if (quoted) {
            if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') out.back() += '"', ++i;
            else if (c == '"') quoted = false;
            else out.back() += c;
        } else if (c == '"') quoted = true;
        else if (c == ',') out.emplace_back();
        else if (c != '\r') out.back() += c;
    }
    return out;
}

}  // namespace

const char* AccuracyCsv::header() { return "knob,value,off,metric,error,unit,better,ms,ms_phase,memory_bytes,scene,camera,actors"; }

AccuracyCsv::AccuracyCsv(const std::string& path) : path_(path), out_(path) {
    if (!out_) throw std::runtime_error("accuracy CSV: cannot write " + path);
    out_ << header() << '\n' << std::flush;
}

void AccuracyCsv::add(const AccuracyRecord& r) {
    const auto bad = [&](const std::string& what) {
        throw std::invalid_argument("accuracy CSV " + path_ + ": knob '" + r.knob + "' value '" + r.value + "': " + what);
    };
    if (r.knob.empty()) bad("the knob has no name");
    if (r.value.empty()) bad("the value is empty");
    if (r.metrics.empty()) bad("no error metric");
    if (r.msPhase.empty()) bad("ms_phase is empty");
    if (!std::isfinite(r.ms) || r.ms < 0) bad("ms is " + number(r.ms) + " (must be finite and not negative)");
    if (!std::isfinite(r.memoryBytes) || r.memoryBytes < 0) bad("memory_bytes is " + number(r.memoryBytes));
    if (r.actors < 0) bad("actors is negative");
    for (const AccuracyMetric& m : r.metrics) {
        if (m.name.empty()) bad("a metric has no name");
        if (m.unit.empty()) bad("metric '" + m.name + "' has no unit");
        if (!std::isfinite(m.value)) bad("metric '" + m.name + "' is " + number(m.value) + " (must be finite)");
    }
    std::ostringstream lines;
    for (const AccuracyMetric& m : r.metrics)
        lines << field(r.knob) << ',' << field(r.value) << ',' << (r.off ? 1 : 0) << ',' << field(m.name) << ',' << number(m.value) << ','
              << field(m.unit) << ',' << (m.lowerIsBetter ? "lower" : "higher") << ',' << number(r.ms) << ',' << field(r.msPhase) << ','
              << number(r.memoryBytes) << ',' << field(r.scene) << ',' << field(r.camera.empty() ? "none" : r.camera) << ',' << r.actors
              << '\n';
    out_ << lines.str();
    out_.flush();
    if (!out_) throw std::runtime_error("accuracy CSV: cannot write " + path_);
}

std::vector<AccuracyRow> readAccuracyCsv(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("accuracy CSV: cannot read " + path);
    std::string line;
    if (!std::getline(in, line)) throw std::runtime_error(path + ": empty file (expected the header '" + AccuracyCsv::header() + "')");
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line != AccuracyCsv::header())
        throw std::runtime_error(path + ":1: not the common accuracy header (expected '" + AccuracyCsv::header() + "')");
    static const char* names[kFields] = {"knob", "value", "off", "metric", "error", "unit", "better",
                                         "ms", "ms_phase", "memory_bytes", "scene", "camera", "actors"};
    std::vector<AccuracyRow> rows;
    int n = 1;
    while (std::getline(in, line)) {
        ++n;
        if (line.empty() || line == "\r") continue;
        const std::vector<std::string> f = split(line);
        const auto where = [&](int column) { return path + ":" + std::to_string(n) + ": column '" + names[column] + "'"; };
        if (int(f.size()) != kFields)
            throw std::runtime_error(path + ":" + std::to_string(n) + ": " + std::to_string(f.size()) + " fields, expected " +
                                     std::to_string(kFields));
        const auto real = [&](int column) {
            const std::string& s = f[std::size_t(column)];
            char* end = nullptr;
            errno = 0;
            const double v = std::strtod(s.c_str(), &end);
            if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE || !std::isfinite(v))
                throw std::runtime_error(where(column) + ": '" + s + "' is not a finite number");
            return v;
        };
        AccuracyRow r;
        r.knob = f[0];
        r.value = f[1];
        if (f[2] != "0" && f[2] != "1") throw std::runtime_error(where(2) + ": '" + f[2] + "' is not 0 or 1");
        r.off = f[2] == "1";
        r.metric.name = f[3];
        r.metric.value = real(4);
        r.metric.unit = f[5];
        if (f[6] != "lower" && f[6] != "higher") throw std::runtime_error(where(6) + ": '" + f[6] + "' is not lower or higher");
        r.metric.lowerIsBetter = f[6] == "lower";
        r.ms = real(7);
        r.msPhase = f[8];
        r.memoryBytes = real(9);
        r.scene = f[10];
        r.camera = f[11];
        const double actors = real(12);
        if (actors < 0 || actors != std::floor(actors)) throw std::runtime_error(where(12) + ": '" + f[12] + "' is not a count");
        r.actors = std::int64_t(actors);
        if (r.knob.empty()) throw std::runtime_error(where(0) + ": empty");
        if (r.metric.name.empty()) throw std::runtime_error(where(3) + ": empty");
        r.file = path;
        r.line = n;
        rows.push_back(std::move(r));
    }
    return rows;
}

std::string sceneName(const std::string& scenePath) { return std::filesystem::path(scenePath).filename().string(); }

}  // namespace throng::sim
