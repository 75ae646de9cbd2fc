// throng-costmodel: reproduces the FMULT cost model of seed 002 (Tables 4-6, Eq. 1-3, Fig. 6),
// lists the paper's inconsistencies, and measures Throng's pipeline against it: the example scene's
// operations counted by the pipeline itself, wall-clock time of both methods as scenes grow, and
// what the LOD scale trades between time and accuracy. --report DIR writes it all (Markdown, CSV,
// PNG charts, JSON).

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "Measurements.h"
#include "ModelTables.h"
#include "TextTable.h"
#include "throng/research/CostModel.h"
#include "throng/scenegraph/WholeFile.h"
#include "throng/sim/AccuracyCsv.h"
#include "throng/support/CommandLine.h"
#include "throng/support/Validators.h"
#include "throng/vtk/Chart.h"

using namespace throng;
using namespace throng::costmodel;
using nlohmann::json;

namespace {

struct Options {
    bool model = false, measure = false, wallclock = false, accuracy = false, json = false;
    std::string fig6Csv, plotPng, reportDir;
    std::size_t maxActors = 1'000'000;
    CostModelFactors factors;
};

// Declares every option of throng-costmodel on `cl`, bound to `o`.
void declare(support::CommandLine& cl, Options& o) {
    using namespace support;
    CLI::App& app = cl.app();
    app.add_flag("--model", o.model, "Tables 5 and 6, the cost expressions and Eq. 3 (default with --measure)");
    app.add_option("--fig6", o.fig6Csv, "Fig. 6 data: improvement factor against AverageCost for (fTrack, fCoh)")
        ->type_name("FILE.csv");
    app.add_option("--plot", o.plotPng, "Fig. 6 as a chart (needs an X display; xvfb-run is used when there is none)")
        ->type_name("FILE.png");
    app.add_flag("--measure", o.measure, "count one frame of the example scene (Tables 2-3) under both methods");
    app.add_flag("--wallclock", o.wallclock, "time both methods on scenes of 100 ... --max-actors actors");
    app.add_option("--max-actors", o.maxActors, "largest wall-clock scene (sizes that do not fit in memory are skipped)")
        ->type_name("N")
        ->check(wholeNumber(0, 1'000'000'000));
    app.add_flag("--accuracy", o.accuracy, "sweep the LOD scale: frame time against joint error and draw-list identity");
    app.add_flag("--json", o.json, "print everything asked for as one JSON object");
    app.add_option("--report", o.reportDir, "all of the above into DIR: report.md, CSV files, PNG charts, costmodel.json")
        ->type_name("DIR")
        ->check(support::folderToWrite());
    // Table 4: counts are numbers of things, the f... factors shares of the actors or nodes.
    const char* group = "Table 4 factors for --model (defaults: the example scene)";
    auto count = [&](const char* name, double& v, const char* what) {
        app.add_option(name, v, what)->type_name("X")->check(nonNegativeNumber())->group(group);
    };
    auto share = [&](const char* name, double& v, const char* what) {
        app.add_option(name, v, what)->type_name("X")->check(number(0.0, 1.0))->group(group);
    };
    CostModelFactors& f = o.factors;
    count("--nActors", f.nActors, "actors");
    share("--fRefpointBsphsIn", f.fRefpointBsphsIn, "share with the Refpoint Bsphere inside the frustum (B)");
    share("--fSklsrootBsphsOut", f.fSklsrootBsphsOut, "share with the Sklsroot Bsphere outside (C1)");
    share("--fSklsrootBsphsIn", f.fSklsrootBsphsIn, "share with the Sklsroot Bsphere inside (C2)");
    share("--fSklsrootBsphsIsect", f.fSklsrootBsphsIsect, "share crossing, internal spheres wholly in or out (C3.1)");
    share("--fCheckIntBsphs", f.fCheckIntBsphs, "share needing culling with internal spheres (C3.2)");
    count("--nSkelsPerActor", f.nSkelsPerActor, "Skeleton nodes per actor");
    count("--nBsphsPerActor", f.nBsphsPerActor, "internal bounding spheres per actor");
    share("--fLODtopo", f.fLODtopo, "share of Skeleton nodes left by skeletal LOD");
}

// VTK (Debian's) renders through X only. Without a display, run again under xvfb-run, or explain.
void ensureDisplay(int argc, char** argv) {
    if (vtk::displayAvailable()) return;
    if (std::getenv("THRONG_UNDER_XVFB")) {
        std::fprintf(stderr, "throng-costmodel: xvfb-run gave no display; charts cannot be drawn\n");
        std::exit(1);
    }
    if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) {
        std::fprintf(stderr, "throng-costmodel: charts need an X display and xvfb-run is not installed: install xvfb "
                             "(./setup.sh does) or run under a display\n");
        std::exit(1);
    }
    setenv("THRONG_UNDER_XVFB", "1", 1);
    // -noreset: otherwise the server resets when one chart's window closes and the next may be refused.
    std::vector<char*> args = {const_cast<char*>("xvfb-run"), const_cast<char*>("-a"), const_cast<char*>("-s"),
                               const_cast<char*>("-screen 0 1280x1024x24 -noreset")};
    static char self[4096];
    const ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
    if (len <= 0) {
        std::fprintf(stderr, "throng-costmodel: cannot find my own executable to re-run under xvfb-run\n");
        std::exit(1);
    }
    self[len] = '\0';
    args.push_back(self);
    for (int i = 1; i < argc; ++i) args.push_back(argv[i]);
    args.push_back(nullptr);
    execvp("xvfb-run", args.data());
    std::perror("throng-costmodel: xvfb-run");
    std::exit(1);
}

// ---- the model ---------------------------------------------------------------------------------

json countsJson(const OperationCounts& n) {
    return {{"NO_01", n.no01}, {"NO_02", n.no02}, {"NO_03", n.no03}, {"NO_04a", n.no04a}, {"NO_04b", n.no04b}, {"NO_05", n.no05}};
}

void writeFig6Csv(const CostModel& model, const std::string& path) {
    std::ostringstream out;
    out << "fTrack,fCoh,AverageCost,factor,factorRecomputed\n";
    for (const Fig6Point& p : fig6(model)) out << p.fTrack << ',' << p.fCoh << ',' << p.averageCost << ',' << p.factor << ',' << p.recomputedFactor << '\n';
    out << "# large-cost limit," << model.largeCostLimit() << '\n';
    writeWholeFile(path, out.str());
}

void plotFig6(const CostModel& model, const std::string& path) {
    vtk::Chart chart;
    chart.title = "Global improvement factor, Eq. 3 as published (seed 002, Fig. 6)";
    chart.xLabel = "AverageCost: FMULT to compute one Skeleton node's DOF values";
    chart.yLabel = "improvement factor (traditional / actor global cost)";
    int colour = 0;
    for (double ft : {0.0, 0.5, 1.0})
        for (double fc : {0.0, 0.5, 1.0}) {
            vtk::ChartSeries s;
            s.name = "fTrack " + fixed(ft, 1) + ", fCoh " + fixed(fc, 1);
            for (const Fig6Point& p : fig6(model, 5.0))
                if (p.fTrack == ft && p.fCoh == fc) {
                    s.x.push_back(p.averageCost);
                    s.y.push_back(p.factor);
                }
            vtk::paletteColour(colour++, s.rgb);
            chart.series.push_back(s);
        }
    vtk::ChartSeries limit;
    limit.name = "large-cost limit " + fixed(model.largeCostLimit(), 2);
    limit.x = {0.0, 1000.0};
    limit.y = {model.largeCostLimit(), model.largeCostLimit()};
    limit.style = vtk::ChartSeries::Style::DashedLine;
    limit.rgb[0] = limit.rgb[1] = limit.rgb[2] = 0;
    chart.series.push_back(limit);
    vtk::writeChartPng(chart, path);
}

std::string modelText(const CostModel& model, bool markdown) {
    std::string out;
    auto table = [&](const TextTable& t) { out += markdown ? t.markdown() : t.text(); };
    out += markdown ? "### Table 5: operations per frame\n\n" : "Table 5: operations per frame\n";
    table(table5(model));
    out += markdown ? "\n### Table 6: FMULT per operation\n\n" : "\nTable 6: FMULT per operation\n";
    table(table6());
    out += markdown ? "\n### Costs and Eq. 3\n\n" : "\nCosts and Eq. 3\n";
    for (const std::string& e : expressions(model)) out += (markdown ? "- `" + e + "`" : "  " + e) + "\n";
    out += markdown ? "\n### Fig. 6 at a few points (Eq. 3 as published; last column recomputed)\n\n"
                    : "\nFig. 6 at a few points (Eq. 3 as published; last column recomputed)\n";
    table(fig6Summary(model));
    return out;
}

// ---- the measurements --------------------------------------------------------------------------

struct CategoryRow {
    const char* name;
    OpCategory matrix;  // operation counts live here
    int value;          // the DOF-value category adding CO_xxa, or -1
};
const CategoryRow kCategories[] = {
    {"NO_01", OpCategory::SkeletonMatrix, static_cast<int>(OpCategory::SkeletonDofValues)},
    {"NO_02", OpCategory::RefpointMatrix, static_cast<int>(OpCategory::RefpointDofValues)},
    {"NO_03", OpCategory::SkeletonRootMatrix, static_cast<int>(OpCategory::SkeletonRootDofValues)},
    {"NO_04a", OpCategory::BsphereRecompute, -1},
    {"NO_04b", OpCategory::BsphereFrustumTest, -1},
    {"NO_05", OpCategory::LodDistance, -1},
};

std::uint64_t measuredOps(const CategoryFigures& f, const CategoryRow& r) { return f.operations[std::size_t(r.matrix)]; }
std::uint64_t measuredFmult(const CategoryFigures& f, const CategoryRow& r) {
    return f.fmult[std::size_t(r.matrix)] + (r.value >= 0 ? f.fmult[std::size_t(r.value)] : 0);
}
double modelOps(const OperationCounts& n, int i) {
    const double v[] = {n.no01, n.no02, n.no03, n.no04a, n.no04b, n.no05};
    return v[i];
}
double modelFmult(const OperationCounts& n, const OperationCosts& c, int i) {
    const double perOp[] = {c.co01a + c.co01b, c.co02a + c.co02b, c.co03a + c.co03b, c.co04a, c.co04b, c.co05};
    return modelOps(n, i) * perOp[i];
}

// Why the measured pipeline does more or less than the model assumes, category by category.
std::vector<std::string> reasons(const ExampleSceneFigures& m) {
    const ActorFrameStatistics& s = m.actorStats;
    const auto posed = s.b + s.c2 + s.c3_1 + s.c3_2;
    const double nodesPerPosed = posed ? double(measuredOps(m.actor, kCategories[0])) / double(posed) : 0.0;
    return {
        "Both methods: same counts as the model where it follows section 4.2. Actor processing poses every actor that "
        "passes CULL 2 (B " + std::to_string(s.b) + " + C2 " + std::to_string(s.c2) + " + C3 " + std::to_string(s.c3_1 + s.c3_2) +
        " = " + std::to_string(posed) + ") with " + fixed(nodesPerPosed, 0) + " active nodes each; Table 5 counts C2 only. Matrix "
        "FMULT per node is what Throng's code does (local matrix from 2 axis rotations, one affine product per level; "
        "traditional also the world matrix), not the paper's 908 / 10 + 53 + 19 + 29.",
        "Every actor's Reference Point, whatever the camera, as the model says. The Reference Point's matrix comes "
        "straight from the behaviour (counted as CO_02a); actors at the scene root need no product with a parent.",
        "Traditional: every actor. Actor processing: every actor that passes CULL 1 (B + C = " + std::to_string(posed + s.c1) +
        "); Table 5 counts B only (nActors x fRefpointBsphsIn).",
        "Traditional: 80 internal spheres + Sklsroot and Refpoint nodes per actor, plus the scene root's group sphere. "
        "Actor processing: the " + std::to_string(s.actorsInScene) + " Refpoint Bspheres placed in the world (the model counts "
        "none), and the internal spheres of every C3 actor (active nodes only), because the internal bound must be "
        "computed to tell C3.1 from C3.2; the model counts C3.2 only, with all 80.",
        "Plane masks: a sphere inside a plane is not tested against it again below, and a sphere inside every plane "
        "stops the tests; the model assumes half of the internal spheres are tested for every crossing actor.",
        "Traditional: only the LOD nodes CULL reaches compute their distance (subtrees of rejected spheres are skipped), "
        "not 41 per actor. Actor processing: one distance per actor that passes CULL 2, not per actor of the scene.",
    };
}

TextTable classificationTable(const ExampleSceneFigures& m) {
    const ActorFrameStatistics& s = m.actorStats;
    TextTable t({"Class", "Table 2", "Measured"});
    t.addRow({"A (Refpoint Bsphere outside)", "20", std::to_string(s.a)});
    t.addRow({"B (Refpoint Bsphere inside)", "30", std::to_string(s.b)});
    t.addRow({"C1 (Sklsroot Bsphere outside)", "20", std::to_string(s.c1)});
    t.addRow({"C2 (Sklsroot Bsphere inside)", "20", std::to_string(s.c2)});
    t.addRow({"C3.1 (internal spheres wholly in or out)", "8", std::to_string(s.c3_1)});
    t.addRow({"C3.2 (internal spheres culled)", "2", std::to_string(s.c3_2)});
    return t;
}

TextTable measuredTable(const ExampleSceneFigures& m, bool withReasons) {
    const CostModel model;
    const OperationCounts tn = model.traditionalCounts(), an = model.actorCounts();
    const OperationCosts tc = CostModel::traditionalCosts(m.averageCost), ac = CostModel::actorCosts(m.averageCost, 1, 1);
    std::vector<std::string> headers = {"Category", "Trad model", "Trad measured", "Actor model", "Actor measured",
                                        "Trad FMULT model", "Trad FMULT measured", "Actor FMULT model", "Actor FMULT measured"};
    if (withReasons) headers.push_back("Why they differ");
    TextTable t(headers);
    const auto why = reasons(m);
    for (int i = 0; i < 6; ++i) {
        const CategoryRow& r = kCategories[i];
        std::vector<std::string> row = {r.name, grouped(modelOps(tn, i)), grouped(double(measuredOps(m.traditional, r))),
                                        grouped(modelOps(an, i)), grouped(double(measuredOps(m.actor, r))),
                                        grouped(modelFmult(tn, tc, i)), grouped(double(measuredFmult(m.traditional, r))),
                                        grouped(modelFmult(an, ac, i)), grouped(double(measuredFmult(m.actor, r)))};
        if (withReasons) row.push_back(why[std::size_t(i)]);
        t.addRow(row);
    }
    double tm = 0, ta = 0, mm = 0, ma = 0;
    for (int i = 0; i < 6; ++i) {
        tm += modelFmult(tn, tc, i);
        ma += modelFmult(an, ac, i);
        ta += double(measuredFmult(m.traditional, kCategories[i]));
        mm += double(measuredFmult(m.actor, kCategories[i]));
    }
    std::vector<std::string> total = {"total", "", "", "", "", grouped(tm), grouped(ta), grouped(ma), grouped(mm)};
    if (withReasons) total.push_back("improvement factor: model " + fixed(tm / ma, 2) + ", measured " + fixed(ta / mm, 2));
    t.addRow(total);
    return t;
}

json measuredJson(const ExampleSceneFigures& m) {
    json j;
    for (const char* method : {"trad", "act"}) {
        const CategoryFigures& f = std::strcmp(method, "trad") == 0 ? m.traditional : m.actor;
        json counts, fmult;
        for (const CategoryRow& r : kCategories) {
            counts[r.name] = measuredOps(f, r);
            fmult[r.name] = measuredFmult(f, r);
        }
        j[method] = counts;
        j["fmult"][method] = fmult;
    }
    const ActorFrameStatistics& s = m.actorStats;
    j["classification"] = {{"A", s.a}, {"B", s.b}, {"C1", s.c1}, {"C2", s.c2}, {"C3_1", s.c3_1}, {"C3_2", s.c3_2}};
    j["averageCost"] = {{"CO_01a", m.averageCost}, {"CO_02a", m.refpointCost}, {"CO_03a", m.skeletonRootCost},
                        {"CO_01a_actor", m.averageCostActor}};
    j["reasons"] = reasons(m);
    // For check_costmodel.py: the elementary operations behind each counter category, and what the
    // verified kernels predict (per-invocation costs and the invocations the cascade calls for).
    auto opsJson = [](const OpTally& t) {
        return json{{"mults", t.mults}, {"adds", t.adds}, {"divs", t.divs}, {"sqrts", t.sqrts}, {"fmult", t.fmult()}};
    };
    for (const char* method : {"trad", "act"}) {
        const CategoryFigures& f = std::strcmp(method, "trad") == 0 ? m.traditional : m.actor;
        for (std::size_t i = 0; i < kOpCategoryCount; ++i)
            j["counters"][method][std::string(opCategoryName(static_cast<OpCategory>(i)))] = opsJson(f.ops[i]);
    }
    const CostModel model;
    const OperationCounts tn = model.traditionalCounts(), an = model.actorCounts();
    const OperationCosts tc = CostModel::traditionalCosts(m.averageCost), ac = CostModel::actorCosts(m.averageCost, 1, 1);
    for (int i = 0; i < 6; ++i) {
        j["modelFmult"]["trad"][kCategories[i].name] = modelFmult(tn, tc, i);
        j["modelFmult"]["act"][kCategories[i].name] = modelFmult(an, ac, i);
    }
    for (const auto& [name, t] : m.kernels.kernels) j["kernels"][name] = opsJson(t);
    j["structure"]["trad"] = m.kernels.traditional;
    j["structure"]["act"] = m.kernels.actor;
    return j;
}

TextTable wallclockTable(const std::vector<WallClockRow>& rows) {
    TextTable t({"Actors", "Posed", "Traditional ms", "Actor ms", "Measured time factor", "Measured FMULT factor",
                 "Model factor (recomputed)", "Model factor (published Eq. 3)"});
    for (const WallClockRow& r : rows)
        t.addRow({grouped(double(r.actors)), grouped(double(r.posed)), fixed(r.traditionalMs, 3), fixed(r.actorMs, 3),
                  fixed(r.timeFactor, 2), fixed(r.fmultFactor, 2), fixed(r.modelFactor, 2), fixed(r.publishedFactor, 2)});
    return t;
}

TextTable accuracyTable(const std::vector<AccuracyRow>& rows) {
    TextTable t({"LOD scale", "APP+CULL ms", "Mean joint error mm", "Max joint error mm", "Draw list identical %",
                 "Skeleton nodes evaluated", "Primitives"});
    for (const AccuracyRow& r : rows)
        t.addRow({r.lodScale < 1e-3 ? "full detail" : fixed(r.lodScale, 2), fixed(r.appCullMs, 3), fixed(r.meanErrorMm, 2), fixed(r.maxErrorMm, 1),
                  fixed(100.0 * r.identicalShare, 1), grouped(double(r.nodesEvaluated)), grouped(double(r.primitives))});
    return t;
}

void plotWallclock(const std::vector<WallClockRow>& rows, const std::string& path) {
    vtk::Chart chart;
    chart.title = "Traditional / actor processing, Table 2 proportions";
    chart.xLabel = "actors in the scene";
    chart.yLabel = "improvement factor";
    chart.logX = true;
    chart.legend = vtk::Chart::Legend::Middle;
    const char* names[] = {"measured APP+CULL time", "measured FMULT", "model, recomputed (measured AverageCost)",
                           "model, Eq. 3 as published"};
    for (int k = 0; k < 4; ++k) {
        vtk::ChartSeries s;
        s.name = names[k];
        s.style = k < 2 ? vtk::ChartSeries::Style::LineAndPoints : vtk::ChartSeries::Style::DashedLine;
        for (const WallClockRow& r : rows) {
            s.x.push_back(double(r.actors));
            s.y.push_back(k == 0 ? r.timeFactor : k == 1 ? r.fmultFactor : k == 2 ? r.modelFactor : r.publishedFactor);
        }
        vtk::paletteColour(k, s.rgb);
        chart.series.push_back(s);
    }
    vtk::writeChartPng(chart, path);
}

void plotAccuracy(const std::vector<AccuracyRow>& rows, const std::string& path) {
    vtk::Chart chart;
    chart.title = "What accuracy costs in time: LOD scale sweep, 3000 walking humanoids";
    chart.xLabel = "mean joint-position error against full detail (mm)";
    chart.yLabel = "APP+CULL time per frame (ms)";
    vtk::ChartSeries s;
    s.name = "full detail (left), then LOD scale " + fixed(rows[1].lodScale, 2) + " to " + fixed(rows.back().lodScale, 2);
    s.style = vtk::ChartSeries::Style::LineAndPoints;
    for (const AccuracyRow& r : rows) {
        s.x.push_back(r.meanErrorMm);
        s.y.push_back(r.appCullMs);
    }
    chart.series.push_back(s);
    vtk::writeChartPng(chart, path);
}

// The LOD-scale sweep in the common accuracy CSV: full detail (the first row) is "off"; the time is
// APP+CULL, the phase the scale changes.
void writeAccuracyCsv(const std::vector<AccuracyRow>& rows, const std::string& path) {
    sim::AccuracyCsv csv(path);
    for (const AccuracyRow& r : rows) {
        sim::AccuracyRecord a;
        a.knob = "lod scale";
        a.off = &r == &rows.front();
        a.value = a.off ? "full detail" : fixed(r.lodScale, 2);
        a.metrics = {{"joint_error_mean", r.meanErrorMm, "mm", true},
                     {"joint_error_max", r.maxErrorMm, "mm", true},
                     {"draw_list_identical", r.identicalShare, "share", false}};
        a.ms = r.appCullMs;
        a.msPhase = "app_cull";
        a.scene = "built-in town spread, 400 m";
        a.camera = "street";
        a.actors = std::int64_t(kAccuracyActors);
        csv.add(a);
    }
}

void write(const std::filesystem::path& path, const std::string& text) { writeWholeFile(path, text); }

const std::vector<std::size_t> kSizes = {100, 1'000, 10'000, 100'000, 1'000'000};
const std::vector<double> kScales = {0.05, 0.1, 0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0};

std::vector<std::size_t> sizesUpTo(std::size_t most) {
    std::vector<std::size_t> s;
    for (std::size_t n : kSizes)
        if (n <= most) s.push_back(n);
    return s;
}

void report(const Options& o) {
    namespace fs = std::filesystem;
    const fs::path dir(o.reportDir);
    fs::create_directories(dir);
    auto progress = [](const std::string& s) { std::fprintf(stderr, "throng-costmodel: %s\n", s.c_str()); };
    const CostModel model(o.factors);
    progress("model and Fig. 6");
    writeFig6Csv(model, (dir / "fig6.csv").string());
    plotFig6(model, (dir / "fig6.png").string());
    progress("measuring the example scene");
    const ExampleSceneFigures measured = measureExampleScene();
    write(dir / "measured.csv", measuredTable(measured, true).csv());
    const auto wall = measureWallClock(sizesUpTo(o.maxActors), progress);
    write(dir / "wallclock.csv", wallclockTable(wall).csv());
    if (!wall.empty()) plotWallclock(wall, (dir / "wallclock.png").string());
    const auto acc = measureAccuracy(kScales, progress);
    writeAccuracyCsv(acc, (dir / "accuracy.csv").string());
    plotAccuracy(acc, (dir / "accuracy.png").string());

    json j;
    j["model"] = {{"trad", countsJson(model.traditionalCounts())}, {"act", countsJson(model.actorCounts())},
                  {"actPublished", countsJson(CostModel::publishedActorCounts())}, {"expressions", expressions(model)}};
    j["fig6"] = json::array();
    for (const Fig6Point& p : fig6(model, 100.0))
        j["fig6"].push_back({{"fTrack", p.fTrack}, {"fCoh", p.fCoh}, {"AverageCost", p.averageCost}, {"factor", p.factor}});
    j["measured"] = measuredJson(measured);
    j["errata"] = CostModel::errata();
    write(dir / "costmodel.json", j.dump(2) + "\n");

    std::string md = "# Throng cost-model report\n\n"
                     "Reproduces the FMULT cost model of Rodriguez, Cerezo, Baldassarri and Seron (2010), *New approaches "
                     "to culling and LOD methods for scenes with multiple virtual actors* (section 6 and appendix), and "
                     "measures Throng's pipeline against it. Regenerate with `benchmarks/run-report DIR`.\n\n"
                     "## 1. The model\n\n" + modelText(model, true) + "\n![Fig. 6](fig6.png)\n\n"
                     "## 2. Where the paper is not consistent\n\n";
    for (const std::string& e : CostModel::errata()) md += "- " + e + "\n";
    md += "\n## 3. The example scene measured\n\nThe scene of Tables 2 and 3 built by `buildCostModelScene` (100 Table 3 "
          "actors placed relative to the camera), one frame under each method with FMULT counting on. Classification "
          "read from the pipeline's statistics:\n\n" + classificationTable(measured).markdown() +
          "\nOperations counted by the pipeline's own counters, beside the model (Table 5 formulas; FMULT at the measured "
          "AverageCost " + fixed(measured.averageCost, 1) + " FMULT per node (CO_01a; CO_02a " + fixed(measured.refpointCost, 1) +
          ", CO_03a " + fixed(measured.skeletonRootCost, 1) + " per actor; posed nodes under actor processing cost " +
          fixed(measured.averageCostActor, 1) + "), with fTrack = fCoh = 1: Throng composes matrices on the CPU and key-frames "
          "move every joint every frame):\n\n" + measuredTable(measured, true).markdown() +
          "\n## 4. Wall clock\n\nAPP+CULL time of both methods on scenes of Table 2's proportions (medians of interleaved "
          "frames), beside the factors the model predicts at the measured AverageCost:\n\n" + wallclockTable(wall).markdown() +
          (wall.empty() ? "" : "\n![Wall clock](wallclock.png)\n") +
          "\n## 5. What accuracy costs in time\n\nThe LOD scale multiplies every distance that selects detail (vaLod levels, "
          "skeletal LOD, behavioural levels). 3000 walking seed humanoids over 400 m x 400 m seen from the street; errors "
          "against full detail (every node active, every behaviour at level 0), joints of actors posed in both:\n\n" +
          accuracyTable(acc).markdown() + "\n![Accuracy and time](accuracy.png)\n\n"
          "## Files\n\n`fig6.csv`, `measured.csv`, `wallclock.csv`, `accuracy.csv` (the common accuracy CSV), `costmodel.json`, and the charts.\n";
    write(dir / "report.md", md);
    progress("report written to " + dir.string());
}

}  // namespace

int main(int argc, char** argv) {
    Options o;
    support::CommandLine cl("throng-costmodel",
                            "The FMULT cost model of Rodriguez et al. 2010 (Tables 4-6, Eq. 1-3, Fig. 6) reproduced,\n"
                            "and Throng's pipeline measured against it. With no option: --model --measure.");
    declare(cl, o);
    if (const auto code = cl.parse(argc, argv)) return *code;
    if (!o.model && !o.measure && !o.wallclock && !o.accuracy && !o.json && o.fig6Csv.empty() && o.plotPng.empty() &&
        o.reportDir.empty())
        o.model = o.measure = true;
    try {
        if (!o.plotPng.empty() || !o.reportDir.empty()) ensureDisplay(argc, argv);
        if (!o.reportDir.empty()) {
            report(o);
            return 0;
        }
        const CostModel model(o.factors);
        auto progress = [](const std::string& s) { std::fprintf(stderr, "throng-costmodel: %s\n", s.c_str()); };
        if (!o.fig6Csv.empty()) writeFig6Csv(model, o.fig6Csv);
        if (!o.plotPng.empty()) plotFig6(model, o.plotPng);
        if (o.json) {
            json j;
            j["model"] = {{"trad", countsJson(model.traditionalCounts())}, {"act", countsJson(model.actorCounts())}};
            j["fig6"] = json::array();
            for (const Fig6Point& p : fig6(model, 100.0))
                j["fig6"].push_back({{"fTrack", p.fTrack}, {"fCoh", p.fCoh}, {"AverageCost", p.averageCost}, {"factor", p.factor}});
            j["measured"] = measuredJson(measureExampleScene());
            j["errata"] = CostModel::errata();
            if (o.wallclock) {
                j["wallclock"] = json::array();
                for (const WallClockRow& r : measureWallClock(sizesUpTo(o.maxActors), progress))
                    j["wallclock"].push_back({{"actors", r.actors}, {"traditionalMs", r.traditionalMs}, {"actorMs", r.actorMs},
                                              {"timeFactor", r.timeFactor}, {"fmultFactor", r.fmultFactor},
                                              {"modelFactor", r.modelFactor}, {"publishedFactor", r.publishedFactor}});
            }
            if (o.accuracy) {
                j["accuracy"] = json::array();
                for (const AccuracyRow& r : measureAccuracy(kScales, progress))
                    j["accuracy"].push_back({{"lodScale", r.lodScale}, {"appCullMs", r.appCullMs}, {"meanErrorMm", r.meanErrorMm},
                                             {"maxErrorMm", r.maxErrorMm}, {"identicalShare", r.identicalShare}});
            }
            std::cout << j.dump(2) << '\n';
            return 0;
        }
        if (o.model) {
            std::cout << modelText(model, false) << "\nErrata (where the paper is not consistent):\n";
            for (const std::string& e : CostModel::errata()) std::cout << "  - " << e << '\n';
        }
        if (o.measure) {
            const ExampleSceneFigures m = measureExampleScene();
            std::cout << "\nThe example scene, one frame under each method (counts from the pipeline's counters):\n"
                      << classificationTable(m).text() << '\n' << measuredTable(m, false).text() << "\nWhy they differ:\n";
            const auto why = reasons(m);
            for (int i = 0; i < 6; ++i) std::cout << "  " << kCategories[i].name << ": " << why[std::size_t(i)] << '\n';
        }
        if (o.wallclock) std::cout << "\nWall clock:\n" << wallclockTable(measureWallClock(sizesUpTo(o.maxActors), progress)).text();
        if (o.accuracy) std::cout << "\nWhat accuracy costs in time:\n" << accuracyTable(measureAccuracy(kScales, progress)).text();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "throng-costmodel: %s\n", e.what());
        return 1;
    }
    return 0;
}
