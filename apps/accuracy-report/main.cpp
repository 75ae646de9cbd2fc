// throng-accuracy-report: what accuracy costs in time, for every approximation at once. Reads every
// common accuracy CSV (sim::AccuracyCsv) in a folder and writes one HTML page that opens from
// disk: per knob a VTK chart of its primary error metric against the time of the phase it changes,
// one series per scene, camera and actor count, each series' Pareto front (least time for a given
// error) and the setting that switches the approximation off marked; a combined table of every
// line; the schema; the crowd's density and speed maps and its fundamental diagram (speed against
// local density, speed_density.csv) when a run wrote them; links to other
// reports. Charts need an X display (xvfb-run -a without one).
//
//   throng-accuracy-report --csv DIR [--out DIR] [--maps DIR] [--link LABEL=PATH ...] [--title TEXT]
// Exit codes: 0 written, 1 a bad CSV or an unwritable file (the message names it, with file and
// line for a CSV), 2 a bad command line.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <compare>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <cstring>
#include <string>
#include <vector>

#include "throng/scenegraph/WholeFile.h"
#include "throng/sim/AccuracyCsv.h"
#include "throng/support/CommandLine.h"
#include "throng/support/Validators.h"
#include "throng/vtk/Chart.h"
#include "throng/vtk/CrowdMaps.h"

namespace fs = std::filesystem;
using throng::sim::AccuracyRow;

namespace {

struct Options {
    std::string csv;                 // folder of common accuracy CSVs
    std::string out = "report";      // where index.html and its pictures go
    std::string maps;                // folder holding density.png, speed.png, speed_density.csv (empty: none)
    std::vector<std::string> links;  // LABEL=PATH, relative to the page
    std::string title = "What accuracy costs in time";
};

// One series of a knob: the lines of one metric measured on one scene, camera and actor count.
struct SeriesKey {
    std::string knob, metric, scene, camera;
    std::int64_t actors = 0;
    auto operator<=>(const SeriesKey&) const = default;
};

SeriesKey keyOf(const AccuracyRow& r) { return {r.knob, r.metric.name, r.scene, r.camera, r.actors}; }

// Marks the rows of one series on its Pareto front: no other row of the series is at most as slow
// and at least as accurate while strictly better in one of the two. Returns one flag per row.
std::vector<bool> paretoFront(const std::vector<const AccuracyRow*>& rows) {
    std::vector<bool> front(rows.size(), true);
    for (std::size_t i = 0; i < rows.size(); ++i)
        for (std::size_t j = 0; j < rows.size() && front[i]; ++j) {
            if (i == j) continue;
            const AccuracyRow& a = *rows[i];
            const AccuracyRow& b = *rows[j];
            const bool lower = a.metric.lowerIsBetter;
            const bool asGood = lower ? b.metric.value <= a.metric.value : b.metric.value >= a.metric.value;
            const bool better = lower ? b.metric.value < a.metric.value : b.metric.value > a.metric.value;
            if (b.ms <= a.ms && asGood && (b.ms < a.ms || better)) front[i] = false;
        }
    return front;
}

std::string html(const std::string& s) {
    std::string o;
    for (char c : s) {
        switch (c) {
            case '&': o += "&amp;"; break;
            case '<': o += "&lt;"; break;
            case '>': o += "&gt;"; break;
            case '"': o += "&quot;"; break;
            default: o += c;
        }
    }
    return o;
}

// A URL path segment or relative path for an href/src: spaces and the few characters HTML or URLs
// would misread, percent-encoded.
std::string href(const std::string& s) {
    std::string o;
    static const char* hex = "0123456789ABCDEF";
    for (unsigned char c : s) {
        if (std::isalnum(c) || std::strchr("/._-~", c)) o += char(c);
        else o += '%', o += hex[c >> 4], o += hex[c & 15];
    }
    return o;
}

std::string number(double v, int digits = 4) {
    std::ostringstream s;
    s.precision(digits);
    s << v;
    return s.str();
}

std::string slug(const std::string& s) {
    std::string o;
    for (unsigned char c : s) {
        if (std::isalnum(c)) o += char(std::tolower(c));
        else if (!o.empty() && o.back() != '-') o += '-';
    }
    while (!o.empty() && o.back() == '-') o.pop_back();
    return o.empty() ? "knob" : o;
}

std::string bytes(double b) {
    if (b <= 0) return "-";
    if (b >= 1048576.0) return number(b / 1048576.0, 3) + " MiB";
    if (b >= 1024.0) return number(b / 1024.0, 3) + " KiB";
    return number(b, 4) + " B";
}

// The metric a knob is plotted by: PSNR where its rows have it (the image error a user sees), else
// the first metric of its first row.
std::string primaryMetric(const std::vector<const AccuracyRow*>& rows) {
    for (const AccuracyRow* r : rows)
        if (r->metric.name == "psnr") return "psnr";
    return rows.front()->metric.name;
}

std::string seriesName(const SeriesKey& k) {
    std::string s = k.scene.empty() ? std::string("no scene") : k.scene;
    if (!k.camera.empty() && k.camera != "none") s += ", " + k.camera;
    if (k.actors > 0) s += ", " + std::to_string(k.actors) + (k.actors == 1 ? " actor" : " actors");
    return s;
}

// Where a picture of `dir` is seen from the page in `out`: its path relative to `out` when it lies
// inside, else a copy under out/maps.
std::string pictureFrom(const fs::path& dir, const std::string& name, const fs::path& out) {
    const fs::path source = fs::weakly_canonical(dir / name);
    const fs::path relative = source.lexically_relative(fs::weakly_canonical(out));
    if (!relative.empty() && *relative.begin() != "..") return relative.generic_string();
    fs::create_directories(out / "maps");
    fs::copy_file(source, out / "maps" / name, fs::copy_options::overwrite_existing);
    return "maps/" + name;
}

// The crowd's fundamental diagram (speed_density.csv of throng-town --vtk) as two charts on the
// page: walking speed against the local density at that moment, and how much of the crowd's time
// was spent at each density or less. Rows with fewer than 1 in 10,000 actor-frames are left out
// of the speed chart (a mean of a handful of walkers says little).
void writeSpeedDensityCharts(std::ostream& page, const std::vector<throng::vtk::SpeedDensityRow>& rows, const fs::path& out) {
    if (rows.empty()) {
        page << "<p>Nobody on the ground was recorded: no speed-density charts.</p>\n";
        return;
    }
    fs::create_directories(out / "plots");
    throng::vtk::Chart speed;
    speed.title = "Walking speed against local density";
    speed.xLabel = "people per square metre in the walker's cell at that moment";
    speed.yLabel = "mean speed (m/s)";
    speed.padding = 0.06;
    speed.width = 900, speed.height = 560;
    throng::vtk::ChartSeries mean;
    mean.name = "mean speed";
    mean.style = throng::vtk::ChartSeries::Style::LineAndPoints;
    throng::vtk::Chart share;
    share.title = "Share of the crowd's time at each local density or less";
    share.xLabel = speed.xLabel;
    share.yLabel = "share of actor-frames on the ground (%)";
    share.padding = 0.06;
    share.legend = throng::vtk::Chart::Legend::Bottom;
    share.width = 900, share.height = 560;
    throng::vtk::ChartSeries cumulative;
    cumulative.name = "at this density or less";
    cumulative.style = throng::vtk::ChartSeries::Style::LineAndPoints;
    throng::vtk::paletteColour(1, cumulative.rgb);
    double sum = 0.0;
    std::size_t kept = 0;
    for (const auto& r : rows) {
        sum += r.share;
        cumulative.x.push_back(r.density);
        cumulative.y.push_back(100.0 * std::min(sum, 1.0));
        if (r.share >= 1e-4) {
            mean.x.push_back(r.density);
            mean.y.push_back(r.meanSpeed);
            ++kept;
        }
    }
    speed.series.push_back(mean);
    share.series.push_back(cumulative);
    throng::vtk::writeChartPng(speed, (out / "plots" / "crowd-speed-density.png").string());
    throng::vtk::writeChartPng(share, (out / "plots" / "crowd-density-share.png").string());
    const double cell = std::sqrt(double(rows.front().people) / rows.front().density);
    page << "<figure><img src=\"plots/crowd-speed-density.png\" alt=\"walking speed against local density\"><figcaption>The crowd's "
            "fundamental diagram: the mean speed of people on the ground (a Reference Point within a metre of the lowest) against the "
            "people sharing their "
         << number(cell) << " m cell at that moment, over every recorded frame (" << kept << " of " << rows.size()
         << " densities, those with at least 1 in 10,000 actor-frames). Drawn with VTK from <code>speed_density.csv</code>."
            "</figcaption></figure>\n"
         << "<figure><img src=\"plots/crowd-density-share.png\" alt=\"share of the crowd's time at each density\"><figcaption>How "
            "crowded it was for the people in it: the share of their time spent at each local density or less (the densest: "
         << number(rows.back().density) << " people per square metre).</figcaption></figure>\n";
}

const char* kSchema = R"(<p>Every sweep writes the <em>common accuracy CSV</em> (<code>throng::sim::AccuracyCsv</code>):
one header line, then one line per knob setting and error metric.</p>
<table><tr><th>column</th><th>meaning</th></tr>
<tr><td><code>knob</code></td><td>the approximation swept, e.g. <code>lod scale</code>, <code>occlusion buffer resolution</code></td></tr>
<tr><td><code>value</code></td><td>its setting, as a user would write it</td></tr>
<tr><td><code>off</code></td><td>1 on the setting that switches the approximation off (its error is zero or at the metric's floor), else 0</td></tr>
<tr><td><code>metric</code></td><td>the error measure of this line, e.g. <code>psnr</code>, <code>ssim</code>, <code>pixels_off_8</code>, <code>joint_error_mean</code>, <code>ncc</code>, <code>path_deviation</code></td></tr>
<tr><td><code>error</code></td><td>its value (finite)</td></tr>
<tr><td><code>unit</code></td><td>its unit: <code>dB</code>, <code>1</code> (dimensionless), <code>share</code> (0 to 1), <code>mm</code>, <code>m</code>, ...</td></tr>
<tr><td><code>better</code></td><td><code>lower</code> or <code>higher</code>: which way the metric improves</td></tr>
<tr><td><code>ms</code></td><td>milliseconds of the phase the knob changes, per frame (or per step, per cell)</td></tr>
<tr><td><code>ms_phase</code></td><td>which time: <code>app_cull</code>, <code>draw</code>, <code>app_cull+draw</code>, <code>step</code>, <code>per_cell</code>, <code>frame</code>, ...</td></tr>
<tr><td><code>memory_bytes</code></td><td>memory the setting holds (0 when none is attributable)</td></tr>
<tr><td><code>scene</code></td><td>the scene file (no directories) or a short name of a built-in scene or asset</td></tr>
<tr><td><code>camera</code></td><td>the camera measured from: <code>street</code>, <code>overview</code>, <code>path</code>, ... or <code>none</code></td></tr>
<tr><td><code>actors</code></td><td>actors (or agents, or characters) measured</td></tr></table>
<p>Fields holding a comma or a quote are quoted as in RFC 4180. The plots show each knob's primary metric (PSNR where the
knob has it, else its first metric) against <code>ms</code>; the Pareto front of a series holds the settings no other
setting of that series beats in both time and error. Metrics that are not errors (such as the share of actors occlusion
hides) say which way is better in <code>better</code>, and the front follows it.</p>
)";

int run(const Options& o) {
    // Every common accuracy CSV of the folder, in name order (errors name the file and line).
    std::vector<fs::path> files;
    for (const fs::directory_entry& e : fs::directory_iterator(o.csv))
        if (e.is_regular_file() && e.path().extension() == ".csv") files.push_back(e.path());
    std::sort(files.begin(), files.end());
    if (files.empty()) throw std::runtime_error("no .csv file in " + o.csv);
    std::vector<AccuracyRow> rows;
    std::vector<std::pair<std::string, std::size_t>> counts;
    for (const fs::path& f : files) {
        std::vector<AccuracyRow> r = throng::sim::readAccuracyCsv(f.string());
        if (r.empty()) throw std::runtime_error(f.string() + ": the header but no line");
        counts.emplace_back(f.filename().string(), r.size());
        rows.insert(rows.end(), std::make_move_iterator(r.begin()), std::make_move_iterator(r.end()));
        std::fprintf(stderr, "throng-accuracy-report: read %s (%zu lines)\n", f.string().c_str(), counts.back().second);
    }

    // Knobs in the order they first appear; series and their Pareto fronts.
    std::vector<std::string> knobs;
    std::map<std::string, std::vector<const AccuracyRow*>> byKnob;
    std::map<SeriesKey, std::vector<const AccuracyRow*>> bySeries;
    for (const AccuracyRow& r : rows) {
        if (!byKnob.count(r.knob)) knobs.push_back(r.knob);
        byKnob[r.knob].push_back(&r);
        bySeries[keyOf(r)].push_back(&r);
    }
    std::map<const AccuracyRow*, bool> onFront;
    for (const auto& [key, series] : bySeries) {
        const std::vector<bool> front = paretoFront(series);
        for (std::size_t i = 0; i < series.size(); ++i) onFront[series[i]] = front[i];
    }

    const fs::path out(o.out);
    fs::create_directories(out / "plots");
    struct Plot {
        std::string knob, metric, unit, better, file;
        std::size_t settings = 0;
        bool hasOff = false;
    };
    std::vector<Plot> plots;
    for (std::size_t k = 0; k < knobs.size(); ++k) {
        const std::string& knob = knobs[k];
        const std::vector<const AccuracyRow*>& all = byKnob[knob];
        Plot p;
        p.knob = knob;
        p.metric = primaryMetric(all);
        std::vector<SeriesKey> keys;
        std::set<std::string> phases;
        for (const AccuracyRow* r : all)
            if (r->metric.name == p.metric) {
                if (std::find(keys.begin(), keys.end(), keyOf(*r)) == keys.end()) keys.push_back(keyOf(*r));
                p.unit = r->metric.unit;
                p.better = r->metric.lowerIsBetter ? "lower" : "higher";
                phases.insert(r->msPhase);
                p.hasOff = p.hasOff || r->off;
                ++p.settings;
            }
        std::string phase;
        for (const std::string& s : phases) phase += (phase.empty() ? "" : ", ") + s;
        throng::vtk::Chart chart;
        chart.title = knob;
        chart.xLabel = "time, " + phase + " (ms)";
        chart.yLabel = p.metric + " (" + p.unit + ", " + p.better + " is better)";
        chart.padding = 0.06;
        // The legend beside the slow and inaccurate corner (what the front avoids): the bottom when
        // higher is better, else the top; the chart leaves room for it there.
        chart.legend = p.better == "higher" ? throng::vtk::Chart::Legend::Bottom : throng::vtk::Chart::Legend::Top;
        chart.width = 900;
        chart.height = 560;
        throng::vtk::ChartSeries off;
        off.name = "off (approximation switched off)";
        off.style = throng::vtk::ChartSeries::Style::Points;
        off.rgb[0] = off.rgb[1] = off.rgb[2] = 0;
        double lo = 1e300, hi = 0;
        for (std::size_t s = 0; s < keys.size(); ++s) {
            std::vector<const AccuracyRow*> series = bySeries[keys[s]];
            std::sort(series.begin(), series.end(), [](const AccuracyRow* a, const AccuracyRow* b) { return a->ms < b->ms; });
            throng::vtk::ChartSeries points, front;
            points.name = seriesName(keys[s]);
            points.style = throng::vtk::ChartSeries::Style::Points;
            front.name = "Pareto front, " + seriesName(keys[s]);
            front.style = throng::vtk::ChartSeries::Style::DashedLine;
            throng::vtk::paletteColour(int(s), points.rgb);
            throng::vtk::paletteColour(int(s), front.rgb);
            for (const AccuracyRow* r : series) {
                points.x.push_back(r->ms);
                points.y.push_back(r->metric.value);
                lo = std::min(lo, r->ms), hi = std::max(hi, r->ms);
                if (onFront[r]) front.x.push_back(r->ms), front.y.push_back(r->metric.value);
                if (r->off) off.x.push_back(r->ms), off.y.push_back(r->metric.value);
            }
            chart.series.push_back(points);
            if (front.x.size() > 1) chart.series.push_back(front);
        }
        if (!off.x.empty()) chart.series.push_back(off);
        chart.logX = lo > 0 && hi / lo > 30.0;  // times from microseconds to seconds stay readable
        // Named after the knob alone, so that a page embedding one plot keeps finding it.
        p.file = "plots/" + slug(knob) + ".png";
        for (int n = 2; std::any_of(plots.begin(), plots.end(), [&](const Plot& q) { return q.file == p.file; }); ++n)
            p.file = "plots/" + slug(knob) + "-" + std::to_string(n) + ".png";
        std::fprintf(stderr, "throng-accuracy-report: plot %zu/%zu: %s\n", k + 1, knobs.size(), knob.c_str());
        throng::vtk::writeChartPng(chart, (out / p.file).string());
        plots.push_back(p);
    }

    std::ostringstream page;
    page << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" << html(o.title) << "</title>\n"
         << "<style>body{font-family:sans-serif;max-width:1200px;margin:auto;padding:1em;color:#222}"
            "table{border-collapse:collapse;font-size:13px;margin:1em 0}td,th{border:1px solid #ccc;padding:2px 6px}"
            "td.n{text-align:right}tr.front td{background:#eef6ee}img{max-width:100%;border:1px solid #ddd}"
            "figure{margin:1em 0}figcaption{font-size:14px;color:#555}</style></head><body>\n"
         << "<h1>" << html(o.title) << "</h1>\n<p>" << rows.size() << " lines from " << files.size() << " common accuracy CSV file"
         << (files.size() == 1 ? "" : "s") << " (";
    for (std::size_t i = 0; i < counts.size(); ++i)
        page << (i ? ", " : "") << "<code>" << html(counts[i].first) << "</code>: " << counts[i].second;
    page << "), " << knobs.size() << " knob" << (knobs.size() == 1 ? "" : "s")
         << ". Each plot shows a knob's primary error metric against the time of the phase it changes; dashed lines join each "
            "series' Pareto front (least time for a given error), black points are the settings that switch the approximation off.</p>\n";
    page << "<h2>Contents</h2><ul>";
    for (const Plot& p : plots) page << "<li><a href=\"#" << slug(p.knob) << "\">" << html(p.knob) << "</a></li>";
    page << "<li><a href=\"#table\">All lines</a></li>";
    if (!o.maps.empty()) page << "<li><a href=\"#maps\">Crowd maps</a></li>";
    if (!o.links.empty()) page << "<li><a href=\"#links\">Other reports</a></li>";
    page << "<li><a href=\"#schema\">Schema</a></li></ul>\n";

    for (const Plot& p : plots) {
        page << "<h2 id=\"" << slug(p.knob) << "\">" << html(p.knob) << "</h2>\n<figure><img src=\"" << href(p.file) << "\" alt=\""
             << html(p.knob + ": " + p.metric + " against time") << "\"><figcaption>" << html(p.metric) << " (" << html(p.unit) << ", "
             << p.better << " is better) against time, " << p.settings << " measured points"
             << (p.hasOff ? "" : "; no setting of this sweep switches the approximation off") << ".</figcaption></figure>\n";
    }

    page << "<h2 id=\"table\">All lines</h2>\n<p>Every line of every file; \"front\": on the Pareto front of its knob, metric, scene, "
            "camera and actor count (shaded).</p>\n<table><tr><th>knob</th><th>value</th><th>off</th><th>metric</th><th>error</th>"
            "<th>unit</th><th>ms</th><th>phase</th><th>memory</th><th>scene</th><th>camera</th><th>actors</th><th>front</th><th>file</th></tr>\n";
    for (const AccuracyRow& r : rows) {
        const bool front = onFront[&r];
        page << "<tr" << (front ? " class=\"front\"" : "") << "><td>" << html(r.knob) << "</td><td>" << html(r.value) << "</td><td>"
             << (r.off ? "off" : "") << "</td><td>" << html(r.metric.name) << "</td><td class=\"n\">" << number(r.metric.value) << "</td><td>"
             << html(r.metric.unit) << "</td><td class=\"n\">" << number(r.ms) << "</td><td>" << html(r.msPhase) << "</td><td class=\"n\">"
             << bytes(r.memoryBytes) << "</td><td>" << html(r.scene) << "</td><td>" << html(r.camera) << "</td><td class=\"n\">" << r.actors
             << "</td><td>" << (front ? "yes" : "") << "</td><td>" << html(fs::path(r.file).filename().string()) << ":" << r.line << "</td></tr>\n";
    }
    page << "</table>\n";

    if (!o.maps.empty()) {
        page << "<h2 id=\"maps\">Crowd maps</h2>\n";
        bool any = false;
        for (const char* name : {"density.png", "speed.png"}) {
            if (!fs::exists(fs::path(o.maps) / name)) {
                std::fprintf(stderr, "throng-accuracy-report: no %s in %s\n", name, o.maps.c_str());
                continue;
            }
            any = true;
            const bool density = std::string(name) == "density.png";
            page << "<figure><img src=\"" << href(pictureFrom(o.maps, name, out)) << "\" alt=\"" << (density ? "crowd density" : "crowd speed")
                 << "\"><figcaption>"
                 << (density ? "Density: people per square metre on the ground, averaged over the recorded frames, dark blue (nobody) to red "
                               "(the densest cell)."
                             : "Speed: mean m/s of those seen in each cell, dark blue (still or nobody) to red (the 95th percentile and faster).")
                 << " Drawn with VTK by <code>throng-town --vtk</code>.</figcaption></figure>\n";
        }
        const fs::path speedDensity = fs::path(o.maps) / "speed_density.csv";
        if (fs::exists(speedDensity)) {
            any = true;
            writeSpeedDensityCharts(page, throng::vtk::readSpeedDensity(speedDensity), out);
        } else {
            std::fprintf(stderr, "throng-accuracy-report: no speed_density.csv in %s\n", o.maps.c_str());
        }
        if (!any) page << "<p>This run wrote no crowd maps.</p>\n";
    }
    if (!o.links.empty()) {
        page << "<h2 id=\"links\">Other reports</h2><ul>\n";
        for (const std::string& l : o.links) {
            const std::size_t eq = l.find('=');
            page << "<li><a href=\"" << href(l.substr(eq + 1)) << "\">" << html(l.substr(0, eq)) << "</a></li>\n";
        }
        page << "</ul>\n";
    }
    page << "<h2 id=\"schema\">Schema</h2>\n" << kSchema << "<pre>" << throng::sim::AccuracyCsv::header() << "</pre>\n</body></html>\n";
    const fs::path index = out / "index.html";
    throng::writeWholeFile(index, page.str());
    std::fprintf(stderr, "throng-accuracy-report: %zu knobs, %zu lines: %s\n", knobs.size(), rows.size(), index.string().c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    throng::support::CommandLine cl("throng-accuracy-report",
                                    "What accuracy costs in time: reads every common accuracy CSV in a folder and writes one HTML page "
                                    "(index.html, opens from disk) with a VTK chart per knob (error against time, Pareto front and "
                                    "'off' marked), a table of every line and the schema. Charts need an X display (xvfb-run -a).");
    CLI::App& app = cl.app();
    app.add_option("--csv", o.csv, "folder of common accuracy CSV files (every *.csv in it is read)")->type_name("DIR")->required()
        ->check(CLI::ExistingDirectory);
    app.add_option("--out", o.out, "where index.html and plots/ go")->type_name("DIR")->capture_default_str()->check(throng::support::folderToWrite());
    app.add_option("--maps", o.maps, "folder holding density.png, speed.png and speed_density.csv (throng-town --vtk DIR)")->type_name("DIR")
        ->check(CLI::ExistingDirectory);
    app.add_option("--link", o.links, "another report linked from the page, its path relative to the page (repeatable)")
        ->type_name("LABEL=PATH")->check(CLI::Validator(
            [](std::string& s) { return s.find('=') == std::string::npos || s.front() == '=' || s.back() == '=' ? std::string("expected LABEL=PATH") : std::string(); },
            "LABEL=PATH"));
    app.add_option("--title", o.title, "the page's title")->capture_default_str();
    if (const auto code = cl.parse(argc, argv)) return *code;
    try {
        if (!throng::vtk::displayAvailable())
            throw std::runtime_error("the charts need an X display (DISPLAY is not set): run under xvfb-run -a");
        return run(o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "throng-accuracy-report: %s\n", e.what());
        return 1;
    }
}
