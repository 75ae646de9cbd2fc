// throng-impostor-quality: how good regenerated impostor cells are, and what they cost (DESIGN.md,
// "Accuracy costs time: show both"). For each character and clip it bakes every key-frame, drops
// the odd ones and regenerates every view of each dropped cell, then compares it with the truly
// rendered cell: NCC (seed 000 Table 2; strict: over the pixels either image covers, and over the
// whole cell), PSNR and SSIM, beside the baselines of showing the previous key-frame and of a plain
// cross-dissolve. Sections (--sections, all by default):
//   morph     the main table: baselines, Beier-Neely with the 4/8/12 strongest bones or all of them
//             (skeleton or interpolated target lines), limb-aware lines, the surface-proxy warp;
//             texture memory with all and half the key-frames
//   features  automatic feature experiments: per-line weights, extra point and outline features,
//             capsules, depth order, the occlusion-aware blend, the surface proxy and its options
//   abp       Beier-Neely a, b, p swept (one at a time) for bone lines and for capsules
//   views     eye directions between the baked views: nearest view, colour blends, and warps
//             (seed 003's interpolated lines, seed 000's view morphing, reprojected bones, proxy)
//   table2    seed 000 Table 2 on our characters: consecutive key-frames and view-points, and
//             in-between key-frames and view-points regenerated with 8 and 12 features and ours
//   memory    the equal-memory comparison (seed 000 §6.2, models M1-M4)
//   runtime   a scene's templates (--scene, throng-town's default) baked and regenerated exactly
//             as throng-town does it, every dropped cell against the truth, GL against CPU
//   half      the half atlas (every other key-frame and view ring dropped, seed 000 §5) against
//             the full atlas, and at twice the cell size: memory, quality shown, quality regenerated
//   sweep     knobs (cell size, views, key-frames kept, features) against accuracy, morph time
//             and texture memory, in the common accuracy CSV
//   throng-impostor-quality ... [--scene FILE]   the scene of the runtime section
// Writes impostor-quality.md, impostor-quality.csv (one row per method and asset),
// impostor-accuracy.csv (the common accuracy CSV, with the view blends timed) and a plot (impostor-quality.png, through VTK: run
// under xvfb-run -a without a display).
//
//   throng-impostor-quality [--out DIR] [--size 128] [--keyframes 16] [--views 16x4]
//                           [--a A --b B --p P] [--asset NAME=SOURCE:CLIP ...] [--sections LIST]
//                           [--sweep-knobs cell_size,views,keyframes_kept,features]
// Exit codes: 0 done, 1 a measurement failed (the message says why), 2 a bad command line.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "throng/scenegraph/WholeFile.h"
#include "throng/testkit/Assets.h"
#include "throng/actors/ActorTemplate.h"
#include "throng/render/BodyLookImage.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/FeatureTrack.h"
#include "throng/render/GpuMorpher.h"
#include "throng/testkit/ImageCompare.h"
#include "throng/render/ImageIO.h"
#include "throng/testkit/ImageSimilarity.h"
#include "throng/render/ImpostorBaker.h"
#include "throng/render/LimbMorph.h"
#include "throng/render/MorphFeatures.h"
#include "throng/render/ProxyWarp.h"
#include "throng/render/ViewWarp.h"
#include "throng/sim/AccuracyCsv.h"
#include "throng/support/SceneImpostors.h"
#include "throng/sim/Simulation.h"
#include "throng/sim/SceneParser.h"
#include "throng/render/ImpostorRenderer.h"
#include "throng/render/GpuProxyWarper.h"
#include "throng/support/CharacterSource.h"
#include "throng/support/CommandLine.h"
#include "throng/support/GlOption.h"
#include "throng/support/Validators.h"
#include "throng/support/ViewGrid.h"
#include "throng/vtk/Chart.h"

namespace {

using namespace throng;

struct Asset {
    std::string name, source, clip;
};

// "NAME=SOURCE:CLIP" (CLIP may be empty: the first clip); std::nullopt when not of that form.
std::optional<Asset> parseAsset(const std::string& text) {
    const auto eq = text.find('='), colon = text.rfind(':');
    if (eq == std::string::npos || eq == 0 || colon == std::string::npos || colon < eq + 2) return std::nullopt;
    return Asset{text.substr(0, eq), text.substr(eq + 1, colon - eq - 1), text.substr(colon + 1)};
}

// Checks --asset values: their form, and that the source is the seed humanoid or an existing file.
CLI::Validator assetValidator() {
    const CLI::Validator source = support::existingFileOr(support::kSeedHumanoid);
    return CLI::Validator(
        [source](std::string& text) -> std::string {
            const auto a = parseAsset(text);
            if (!a) return "expects NAME=SOURCE:CLIP (CLIP may be empty), got '" + text + "'";
            std::string path = a->source;
            return source(path);
        },
        "");
}

const std::vector<std::string> kSections = {"morph", "features", "abp", "views", "table2", "memory", "half", "sweep", "runtime"};

double ms(std::chrono::steady_clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

double mean(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

double stdev(const std::vector<double>& v) {
    const double m = mean(v);
    double var = 0;
    for (double x : v) var += (x - m) * (x - m);
    return v.size() > 1 ? std::sqrt(var / static_cast<double>(v.size() - 1)) : 0.0;
}

// The metrics of approximations against truths.
struct Scores {
    std::vector<double> ncc, nccWhole, psnr, ssim, mse;
    double morphMs = 0;
    int morphs = 0;
    void add(const Image& approx, const Image& truth) {
        ncc.push_back(testkit::normalizedCrossCorrelation(approx, truth));
        nccWhole.push_back(testkit::normalizedCrossCorrelation(approx, truth, false));
        const double p = testkit::compareImages(approx, truth).psnr;
        psnr.push_back(std::min(p, 99.0));
        mse.push_back(std::isfinite(p) ? 255.0 * 255.0 * std::pow(10.0, -p / 10.0) : 0.0);
        ssim.push_back(testkit::structuralSimilarity(approx, truth));
    }
    double msPerMorph() const { return morphs ? morphMs / morphs : 0.0; }
    // PSNR of the mean squared error over every image (exact images do not count as 99 dB).
    double pooledPsnr() const {
        const double m = mean(mse);
        return m > 0 ? 10.0 * std::log10(255.0 * 255.0 / m) : 99.0;
    }
};

// One row of a results table.
struct Row {
    std::string section, asset, clip, method, path;
    int features = -1;  // -1: not a morph
    double ncc = 0, nccStd = 0, nccWhole = 0, nccWholeStd = 0, psnr = 0, ssim = 0, msPerCell = 0;
    int cells = 0;
    std::size_t bytes = 0;  // texture plus feature memory, when the section reports it
    std::string note;       // e.g. the in-between share for the equal-memory table
    double extra = 0;       // section-specific figure (NCC over the in-betweens only)
};

Row makeRow(std::string section, const std::string& asset, const std::string& clip, std::string method, const Scores& s) {
    Row r;
    r.section = std::move(section);
    r.asset = asset;
    r.clip = clip;
    r.method = std::move(method);
    r.ncc = mean(s.ncc);
    r.nccStd = stdev(s.ncc);
    r.nccWhole = mean(s.nccWhole);
    r.nccWholeStd = stdev(s.nccWhole);
    r.psnr = mean(s.psnr);
    r.ssim = mean(s.ssim);
    r.cells = static_cast<int>(s.ncc.size());
    r.msPerCell = s.msPerMorph();
    return r;
}

// One row of the common accuracy CSV.
struct AccuracyRow {
    std::string knob, value, method, scene, measure;
    double ncc = 0, nccStd = 0, nccWhole = 0, psnr = 0, ssim = 0, msPerCell = 0;
    int samples = 0;
    std::size_t bytes = 0;
};

// ------------------------------------------------------------------------------------------------
// A bake: one template and clip at one cell size, views and key-frame count, with everything the
// methods read (the full atlas is the truth for baked cells, the half one is what is stored).
struct Bake {
    ImpostorBakeOptions options;
    std::shared_ptr<GlContext> context;
    std::unique_ptr<ImpostorBaker> baker;
    std::unique_ptr<ImpostorAtlas> full, half;
    std::unique_ptr<FeatureTrack> track;
    std::unique_ptr<GpuMorpher> gpu;
    std::map<std::pair<long, int>, ProxyMesh> proxies;  // by vertex budget (0: every vertex, copies welded) and poses per key-frame

    const ProxyMesh& proxy(long budget, int samples = 1) {
        auto it = proxies.find({budget, samples});
        if (it == proxies.end())
            it = proxies.emplace(std::pair{budget, samples}, baker->proxyMesh(static_cast<std::size_t>(budget), samples)).first;
        return it->second;
    }
    // Bytes of the bone lines every cell keeps (what the line morph reads beside the pages).
    std::size_t lineBytes() const {
        return full->boneCount() * full->views().viewCount() * static_cast<std::size_t>(full->keyframeCount()) * sizeof(FeatureLine);
    }
};

// --gl: the kind of context every bake of the run is made in.
GlApi bakeGl = GlApi::Auto;

std::unique_ptr<Bake> makeBake(std::shared_ptr<const ActorTemplate> tmpl, int clip, const ImpostorBakeOptions& options) {
    auto b = std::make_unique<Bake>();
    b->options = options;
    b->context = createContext({.width = options.cellSize, .height = options.cellSize, .api = bakeGl});
    b->baker = std::make_unique<ImpostorBaker>(b->context, std::move(tmpl), clip, options);
    b->full = std::make_unique<ImpostorAtlas>(b->baker->bake());
    b->half = std::make_unique<ImpostorAtlas>(*b->full);
    b->half->dropOddKeyframes();
    b->track = std::make_unique<FeatureTrack>(b->baker->featureTrack());
    b->gpu = std::make_unique<GpuMorpher>(b->context);
    return b;
}

// How a dropped cell is regenerated.
struct Method {
    enum class Kind { Previous, Lines, Limbs, Proxy, OracleLines, OracleProxy };
    std::string name;
    Kind kind = Kind::Lines;
    FeatureOptions features{};
    MorphParameters parameters{};
    bool interpolated = false;  // target lines interpolated from the neighbours (the paper)
    VisibilityOptions visibility{};
    ProxyWarpOptions proxyOptions{};
    long proxyBudget = 0;
    bool direct = false;  // sweep only: warp straight to each sample's eye and time (no cells shared)
    int proxySamples = 1;  // direct only: proxy poses per key-frame interval
};

// The surface-proxy options this report recommends (from the features section).
ProxyWarpOptions ourProxyOptions() {
    ProxyWarpOptions o;
    o.opaqueInside = true;
    return o;
}

Method linesMethod(std::string name, std::size_t bones, const MorphParameters& p, bool capsules = false) {
    Method m;
    m.name = std::move(name);
    m.features.bones = bones;
    m.features.capsules = capsules;
    m.parameters = p;
    return m;
}

// Our line features (GPU-able): every bone as a capsule, depth order 0.1/px (from the features
// section: capsules help every asset, depth order the robot).
Method oursLines(std::string name, std::size_t bones, const MorphParameters& p) {
    Method m = linesMethod(std::move(name), bones, p, true);
    m.parameters.depth = 0.1f;
    return m;
}

Method proxyMethod(std::string name, ProxyWarpOptions o = ourProxyOptions(), long budget = 0) {
    Method m;
    m.name = std::move(name);
    m.kind = Method::Kind::Proxy;
    m.proxyOptions = o;
    m.proxyBudget = budget;
    return m;
}

// Per pixel, whichever of two images is nearer the truth (a bound on any blend of them).
Image perPixelBest(const Image& a, const Image& b, const Image& truth) {
    Image best = a;
    for (std::size_t i = 0; i < best.rgba.size(); i += 4) {
        int ea = 0, eb = 0;
        for (int c = 0; c < 4; ++c) ea += std::abs(a.rgba[i + c] - truth.rgba[i + c]), eb += std::abs(b.rgba[i + c] - truth.rgba[i + c]);
        if (eb < ea) std::copy_n(&b.rgba[i], 4, &best.rgba[i]);
    }
    return best;
}

// The cell of dropped key-frame `k` in view `v` of `bake.half` as `m` regenerates it; the time it
// took goes into `s`. `truth` only for the oracle rows.
Image regenerate(Bake& bake, const Method& m, std::uint32_t v, int k, Scores& s, const Image* truth = nullptr) {
    const ImpostorAtlas& half = *bake.half;
    int before = 0, after = 0;
    float t = 0.5f;
    half.neighbours(k, before, after, t);
    const Image a = half.cell(v, before), b = half.cell(v, after);
    if (m.kind == Method::Kind::Previous) return half.cell(v, (k - 1 + half.keyframeCount()) % half.keyframeCount());
    const auto t0 = std::chrono::steady_clock::now();
    Image out;
    if (m.kind == Method::Kind::Proxy || m.kind == Method::Kind::OracleProxy) {
        const ProxyMesh& proxy = bake.proxy(m.proxyBudget);
        const glm::vec3 eye = half.views().direction(v);
        const ProxySource sources[2] = {{&a, eye, before, 1.0f - t}, {&b, eye, after, t}};
        if (m.kind == Method::Kind::Proxy) out = warpProxy(proxy, sources, eye, k, m.proxyOptions);
        else out = perPixelBest(warpProxy(proxy, std::span(sources, 1), eye, k, m.proxyOptions),
                                warpProxy(proxy, std::span(sources + 1, 1), eye, k, m.proxyOptions), *truth);
    } else {
        CellFeatures f = droppedCellFeatures(half, *bake.track, v, k, m.features);
        if (m.interpolated) {
            interpolateLines(f.from, f.to, t, f.target);
            f.targetAttributes.clear();
        }
        if (m.kind == Method::Kind::Limbs) out = morphLimbs(a, b, f, *bake.track, t, m.parameters, m.visibility, 2);
        else if (m.kind == Method::Kind::OracleLines)
            out = perPixelBest(morphImages(a, f.from, b, f.to, f.target, 0.0f, m.parameters, 2, f.targetAttributes),
                               morphImages(a, f.from, b, f.to, f.target, 1.0f, m.parameters, 2, f.targetAttributes), *truth);
        else if (f.target.size() <= GpuMorpher::kMaxLines)
            out = bake.gpu->morph(a, f.from, b, f.to, f.target, t, m.parameters, f.targetAttributes);
        else
            out = morphImages(a, f.from, b, f.to, f.target, t, m.parameters, 2, f.targetAttributes);
    }
    s.morphMs += ms(std::chrono::steady_clock::now() - t0);
    ++s.morphs;
    return out;
}

std::string pathOf(const Bake& bake, const Method& m) {
    switch (m.kind) {
        case Method::Kind::Previous: return "-";
        case Method::Kind::Lines: {
            const std::size_t per = m.features.extra == ExtraFeatures::None ? 1 : m.features.extra == ExtraFeatures::Midpoints ? 2
                                                                             : m.features.extra == ExtraFeatures::JointPoints ? 4 : 3;
            return std::min(m.features.bones, bake.half->boneCount()) * per <= GpuMorpher::kMaxLines ? "GPU" : "CPU, 2 threads";
        }
        case Method::Kind::Limbs: return "CPU, 2 threads";
        case Method::Kind::Proxy: return "CPU, 1 thread";
        default: return "oracle";
    }
}

int featureCount(Bake& bake, const Method& m) {
    if (m.kind == Method::Kind::Previous) return -1;
    if (m.kind == Method::Kind::Proxy || m.kind == Method::Kind::OracleProxy) return static_cast<int>(bake.proxy(m.proxyBudget).vertexCount());
    int before = 0, after = 0;
    float t = 0;
    bake.half->neighbours(1, before, after, t);
    return static_cast<int>(droppedCellFeatures(*bake.half, *bake.track, 0, 1, m.features).target.size());
}

// Every view of every dropped key-frame regenerated by `m`, against the truly rendered cell.
Row measureDropped(const std::string& section, const Asset& asset, Bake& bake, const Method& m, bool log = true) {
    Scores s;
    const ImpostorAtlas& half = *bake.half;
    for (int k = 1; k < half.keyframeCount(); k += 2) {
        if (half.stored(k)) continue;
        for (std::uint32_t v = 0; v < half.views().viewCount(); ++v) {
            const Image truth = bake.full->cell(v, k);
            s.add(regenerate(bake, m, v, k, s, &truth), truth);
        }
    }
    Row r = makeRow(section, asset.name, bake.full->clipName(), m.name, s);
    r.features = featureCount(bake, m);
    r.path = pathOf(bake, m);
    if (log)
        std::fprintf(stderr, "%s: [%s] %s: NCC %.4f (whole %.4f) PSNR %.2f SSIM %.4f, %.2f ms/cell\n", asset.name.c_str(), section.c_str(),
                     m.name.c_str(), r.ncc, r.nccWhole, r.psnr, r.ssim, r.msPerCell);
    return r;
}

// ------------------------------------------------------------------------------------------------
// Sections.

void sectionMorph(const Asset& asset, Bake& bake, const MorphParameters& p, const std::filesystem::path& out, std::vector<Row>& rows) {
    const std::size_t all = bake.half->boneCount();
    std::vector<Method> methods;
    Method previous;
    previous.name = "previous key-frame";
    previous.kind = Method::Kind::Previous;
    methods.push_back(previous);
    methods.push_back(linesMethod("cross-dissolve", 0, p));
    for (std::size_t f : {std::size_t{4}, std::size_t{8}, std::size_t{12}})
        if (f < all) methods.push_back(linesMethod("morph, strongest bones", f, p));
    methods.push_back(linesMethod("morph, all bones", all, p));
    Method interpolated = linesMethod("morph, all bones, interpolated lines (paper)", all, p);
    interpolated.interpolated = true;
    methods.push_back(interpolated);
    methods.push_back(oursLines("morph, all bones as capsules + depth order (ours, lines)", all, p));
    methods.push_back(proxyMethod("surface-proxy warp (ours)"));
    for (const Method& m : methods) rows.push_back(measureDropped("morph", asset, bake, m));
    // One cell of each, for looking at: view 4 (a three-quarter view with the default 16x4), or
    // the last of fewer views.
    const std::uint32_t v = std::min<std::uint32_t>(4, bake.full->views().viewCount() - 1);
    Scores unused;
    writePng(bake.full->cell(v, 1), out / (asset.name + "-truth.png"));
    writePng(bake.half->cell(v, 0), out / (asset.name + "-previous.png"));
    writePng(regenerate(bake, linesMethod("", all, p), v, 1, unused), out / (asset.name + "-morphed.png"));
    writePng(regenerate(bake, proxyMethod(""), v, 1, unused), out / (asset.name + "-proxy.png"));
}

void sectionFeatures(const Asset& asset, Bake& bake, const MorphParameters& p, std::vector<Row>& rows) {
    const std::size_t all = bake.half->boneCount();
    std::vector<Method> methods;
    const auto lines = [&](std::string name, auto edit) {
        Method m = linesMethod(std::move(name), all, p);
        edit(m);
        methods.push_back(m);
    };
    lines("bone lines (classic weights)", [](Method&) {});
    lines("bone lines, weights by bone length", [](Method& m) { m.features.weighting = LineWeighting::Length; });
    lines("bone lines, weights by motion between the neighbours", [](Method& m) { m.features.weighting = LineWeighting::Motion; });
    lines("bone lines + midpoints", [](Method& m) { m.features.extra = ExtraFeatures::Midpoints; });
    lines("bone lines + joint and midpoints", [](Method& m) { m.features.extra = ExtraFeatures::JointPoints; });
    lines("bone lines + outline lines either side", [](Method& m) { m.features.extra = ExtraFeatures::Silhouettes; });
    for (float r : {0.5f, 0.75f, 1.0f, 1.25f, 1.5f}) {
        char name[64];
        std::snprintf(name, sizeof name, "capsules, radius x %.2f", static_cast<double>(r));
        lines(name, [r](Method& m) { m.features.capsules = true, m.features.radiusScale = r; });
    }
    lines("capsules + length weights", [](Method& m) { m.features.capsules = true, m.features.weighting = LineWeighting::Length; });
    for (float d : {0.1f, 0.3f, 1.0f}) {
        char name[64];
        std::snprintf(name, sizeof name, "capsules + depth order %.1f/px", static_cast<double>(d));
        lines(name, [d](Method& m) { m.features.capsules = true, m.parameters.depth = d; });
    }
    lines("capsules + occlusion-aware blend", [](Method& m) { m.features.capsules = true, m.kind = Method::Kind::Limbs; });
    lines("capsules + depth 0.3 + occlusion-aware blend",
          [](Method& m) { m.features.capsules = true, m.parameters.depth = 0.3f, m.kind = Method::Kind::Limbs; });
    lines("bound: per-pixel best of the two bone-line warps (uses the truth)", [](Method& m) { m.kind = Method::Kind::OracleLines; });
    lines("bound: per-pixel best of the two capsule warps (uses the truth)",
          [](Method& m) { m.features.capsules = true, m.kind = Method::Kind::OracleLines; });

    ProxyWarpOptions o = ourProxyOptions();
    methods.push_back(proxyMethod("surface proxy, premultiplied blend (alpha from the sources)", [] {
        ProxyWarpOptions x;
        x.opaqueInside = false;
        return x;
    }()));
    methods.push_back(proxyMethod("surface proxy, opaque inside (ours)", o));
    ProxyWarpOptions x = o;
    x.distrust = 1.0f;
    methods.push_back(proxyMethod("surface proxy, no visibility test", x));
    x = o, x.depthTolerance = 4.0f;
    methods.push_back(proxyMethod("surface proxy, depth tolerance 4 px", x));
    x = o, x.bicubic = true;
    methods.push_back(proxyMethod("surface proxy, bicubic sampling", x));
    x = o, x.normalSharpness = 16.0f;
    methods.push_back(proxyMethod("surface proxy, normal-alike weights (16)", x));
    x = o, x.rim = 2;
    methods.push_back(proxyMethod("surface proxy, 2 px rim beyond the outline", x));
    for (long budget : {2000L, 1000L, 500L}) methods.push_back(proxyMethod("surface proxy of <= " + std::to_string(budget) + " vertices", o, budget));
    x = o, x.rim = 1;
    methods.push_back(proxyMethod("surface proxy of <= 1000 vertices, 1 px rim", x, 1000));
    Method bound = proxyMethod("bound: per-pixel best of the two proxy warps (uses the truth)", o);
    bound.kind = Method::Kind::OracleProxy;
    methods.push_back(bound);
    for (const Method& m : methods) rows.push_back(measureDropped("features", asset, bake, m));
}

void sectionAbp(const Asset& asset, Bake& bake, const MorphParameters& p, std::vector<Row>& rows) {
    const std::size_t all = bake.half->boneCount();
    for (bool capsules : {false, true}) {
        const auto run = [&](MorphParameters q) {
            char name[96];
            std::snprintf(name, sizeof name, "%s, a %.2f b %.2f p %.2f", capsules ? "capsules" : "bone lines", static_cast<double>(q.a),
                          static_cast<double>(q.b), static_cast<double>(q.p));
            rows.push_back(measureDropped("abp", asset, bake, linesMethod(name, all, q, capsules)));
        };
        for (float a : {0.1f, 0.25f, 0.5f, 1.0f, 2.0f, 4.0f}) run({a, p.b, p.p, p.depth});
        for (float b : {1.0f, 1.5f, 2.0f, 3.0f, 4.0f, 6.0f}) run({p.a, b, p.p, p.depth});
        for (float pp : {0.0f, 0.25f, 0.75f, 1.0f}) run({p.a, p.b, pp, p.depth});
    }
}

// Premultiplied weighted sum of cells.
Image blendCells(std::span<const Image> cells, std::span<const float> weights) {
    Image out = cells.front();
    std::vector<float> acc(out.rgba.size(), 0.0f);
    for (std::size_t i = 0; i < cells.size(); ++i) {
        if (weights[i] <= 0.0f) continue;
        for (std::size_t j = 0; j < acc.size(); ++j) acc[j] += weights[i] * static_cast<float>(cells[i].rgba[j]);
    }
    for (std::size_t j = 0; j < acc.size(); ++j) out.rgba[j] = static_cast<std::uint8_t>(std::clamp(std::lround(acc[j]), 0L, 255L));
    return out;
}

// The ways of showing a view between baked ones, at a stored key-frame, from the three views of
// `blend` (seed 003's cell).
struct ViewShow {
    std::string name;
    // 0 nearest, 1 colour blend, 2 smoothstep colour blend, 3 seed 003 lines, 4 seed 000 view
    // morph, 5 reprojected bones, 6 reprojected capsules, 7 surface proxy
    int kind = 0;
};

const std::vector<ViewShow>& viewShows() {
    static const std::vector<ViewShow> shows = {
        {"nearest view (snapping)", 0},
        {"barycentric colour blend of 3 views", 1},
        {"smoothstep-biased colour blend", 2},
        {"warp to barycentric bone lines, then blend (seed 003)", 3},
        {"view morphing: blended lines + postwarp (seed 000)", 4},
        {"warp to the bones reprojected for the eye (ours)", 5},
        {"warp to reprojected capsules + depth order (ours, lines)", 6},
        {"surface proxy from the 3 views (ours)", 7},
    };
    return shows;
}

// The cell from direction `eye` at stored key-frame `k` shown as `kind` from views `views` with
// `weights` (at least one of weight > 0).
Image showView(Bake& bake, int kind, const glm::vec3& eye, int k, std::span<const std::uint32_t> views, std::span<const float> weights,
               const MorphParameters& p, Scores& s) {
    const ImpostorAtlas& full = *bake.full;
    std::vector<Image> cells;
    std::vector<std::vector<FeatureLine>> lines;
    std::vector<glm::vec3> directions;
    for (std::uint32_t v : views) {
        cells.push_back(full.cell(v, k));
        const auto l = full.lines(v, k);
        lines.emplace_back(l.begin(), l.end());
        directions.push_back(full.views().direction(v));
    }
    const auto t0 = std::chrono::steady_clock::now();
    Image out;
    if (kind == 1) {
        out = blendCells(cells, weights);
    } else if (kind == 7) {
        std::vector<ProxySource> sources;
        for (std::size_t i = 0; i < views.size(); ++i) sources.push_back({&cells[i], directions[i], k, weights[i]});
        out = warpProxy(bake.proxy(0), sources, eye, k, ourProxyOptions());
    } else {
        std::vector<FeatureLine> target;
        std::vector<LineAttributes> attributes;
        if (kind == 3) target = blendViewLines(lines, weights);
        else if (kind == 4) target = postwarpLines(blendViewLines(lines, weights), viewPostwarp(directions, weights, eye), full.cellSize());
        else {
            target = bake.track->lines(k, eye);
            if (kind == 6) {
                FeatureOptions fo;
                fo.capsules = true;
                std::vector<std::uint32_t> all(target.size());
                for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<std::uint32_t>(i);
                viewFeatures(*bake.track, k, eye, all, std::vector<float>(target.size(), 1.0f), fo, target, attributes);
            }
        }
        MorphParameters q = p;
        if (kind == 6) q.depth = 0.1f;  // as oursLines()
        out = warpViews(cells, lines, weights, target, q, attributes, bake.gpu.get());
    }
    s.morphMs += ms(std::chrono::steady_clock::now() - t0);
    ++s.morphs;
    return out;
}

void sectionViews(const Asset& asset, Bake& bake, const MorphParameters& p, std::vector<Row>& rows) {
    const ViewHemisphere& h = bake.full->views();
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> az(0.0f, 6.2831853f), el(0.0f, h.elevation(h.elevations() - 1));
    std::vector<Scores> scores(viewShows().size());
    for (int i = 0; i < 96; ++i) {
        const float a = az(rng), e = el(rng);
        const glm::vec3 dir(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
        const int k = 2 * (i % (bake.full->keyframeCount() / 2));
        const Image truth = bake.baker->renderCell(bake.full->duration() * k / bake.full->keyframeCount(), dir);
        const ViewBlend linear = h.blend(dir, false), smooth = h.blend(dir, true);
        for (const ViewShow& show : viewShows()) {
            Scores& s = scores[static_cast<std::size_t>(show.kind)];
            if (show.kind == 0) {
                const auto t0 = std::chrono::steady_clock::now();
                const Image nearest = bake.full->cell(h.nearest(dir), k);
                s.morphMs += ms(std::chrono::steady_clock::now() - t0);
                ++s.morphs;
                s.add(nearest, truth);
                continue;
            }
            const ViewBlend& b = show.kind == 2 ? smooth : linear;
            s.add(showView(bake, show.kind == 2 ? 1 : show.kind, dir, k, b.views, b.weights, p, s), truth);
        }
    }
    for (const ViewShow& show : viewShows()) {
        Row r = makeRow("views", asset.name, bake.full->clipName(), show.name, scores[static_cast<std::size_t>(show.kind)]);
        r.path = show.kind <= 2 || show.kind == 7 ? "CPU, 1 thread" : "GPU";
        rows.push_back(r);
        std::fprintf(stderr, "%s: [views] %s: NCC %.4f PSNR %.2f SSIM %.4f\n", asset.name.c_str(), show.name.c_str(), r.ncc, r.psnr, r.ssim);
    }
}

void sectionTable2(const Asset& asset, Bake& bake, const MorphParameters& p, std::vector<Row>& rows) {
    const ImpostorAtlas& full = *bake.full;
    const std::string clip = full.clipName();
    const std::size_t all = full.boneCount();
    // Key-frames: the dropped ones against their previous key-frame, and regenerated.
    Method previous;
    previous.name = "Cons. key-frames";
    previous.kind = Method::Kind::Previous;
    rows.push_back(measureDropped("table2", asset, bake, previous));
    for (std::size_t f : {std::size_t{8}, std::size_t{12}})
        rows.push_back(measureDropped("table2", asset, bake, linesMethod("Int. key-frames (" + std::to_string(f) + ")", std::min(f, all), p)));
    rows.push_back(measureDropped("table2", asset, bake, oursLines("Int. key-frames (all bones as capsules + depth, ours)", all, p)));
    rows.push_back(measureDropped("table2", asset, bake, proxyMethod("Int. key-frames (surface proxy, ours)")));

    // View-points: every odd azimuth of each stored key-frame regenerated from its two azimuth
    // neighbours (as if the grid had half the azimuths), against the baked view.
    const int azimuths = full.views().azimuths();
    Scores cons, int8, int12, intAll, intProxy;
    for (int k = 0; k < full.keyframeCount(); k += 2)
        for (int ring = 0; ring < full.views().elevations(); ++ring)
            for (int a = 1; a < azimuths; a += 2) {
                const auto view = [&](int az) { return static_cast<std::uint32_t>(ring * azimuths + (az + azimuths) % azimuths); };
                const Image truth = full.cell(view(a), k);
                cons.add(full.cell(view(a - 1), k), truth);
                const std::uint32_t pair[2] = {view(a - 1), view(a + 1)};
                const float half[2] = {0.5f, 0.5f};
                const glm::vec3 eye = full.views().direction(view(a));
                for (auto [scores, count] : {std::pair<Scores*, std::size_t>{&int8, 8}, {&int12, 12}}) {
                    // Seed 000's view morphing with the strongest bones.
                    const std::vector<std::uint32_t> bones = full.strongestBones(count);
                    std::vector<Image> cells{full.cell(pair[0], k), full.cell(pair[1], k)};
                    std::vector<std::vector<FeatureLine>> lines(2);
                    for (int i = 0; i < 2; ++i)
                        for (std::uint32_t b : bones) lines[static_cast<std::size_t>(i)].push_back(full.lines(pair[i], k)[b]);
                    const glm::vec3 dirs[2] = {full.views().direction(pair[0]), full.views().direction(pair[1])};
                    const auto t0 = std::chrono::steady_clock::now();
                    const std::vector<FeatureLine> target =
                        postwarpLines(blendViewLines(lines, half), viewPostwarp(dirs, half, eye), full.cellSize());
                    scores->add(warpViews(cells, lines, half, target, p, {}, bake.gpu.get()), truth);
                    scores->morphMs += ms(std::chrono::steady_clock::now() - t0);
                    ++scores->morphs;
                }
                intAll.add(showView(bake, 6, eye, k, pair, half, p, intAll), truth);
                intProxy.add(showView(bake, 7, eye, k, pair, half, p, intProxy), truth);
            }
    for (auto [name, s] : {std::pair<const char*, Scores*>{"Cons. view-points", &cons},
                           {"Int. view-points (8)", &int8},
                           {"Int. view-points (12)", &int12},
                           {"Int. view-points (all bones as capsules + depth, reprojected, ours)", &intAll},
                           {"Int. view-points (surface proxy, ours)", &intProxy}}) {
        rows.push_back(makeRow("table2", asset.name, clip, name, *s));
        std::fprintf(stderr, "%s: [table2] %s: NCC %.4f +- %.4f\n", asset.name.c_str(), name, rows.back().ncc, rows.back().nccStd);
    }
}

// `image` resampled to `size` pixels square, premultiplied: bilinear when enlarging, the mean of
// 4 x 4 bilinear samples over each pixel's footprint when shrinking (no aliasing).
Image resample(const Image& image, int size) {
    if (image.width == size && image.height == size) return image;
    Image out;
    out.name = image.name;
    out.width = out.height = size;
    out.rgba.resize(static_cast<std::size_t>(size) * size * 4);
    const float sx = static_cast<float>(image.width) / static_cast<float>(size);
    const float sy = static_cast<float>(image.height) / static_cast<float>(size);
    const int taps = sx > 1.0f || sy > 1.0f ? 4 : 1;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            float acc[4] = {0, 0, 0, 0};
            for (int j = 0; j < taps; ++j)
                for (int i = 0; i < taps; ++i) {
                    float c[4];
                    const float fx = (static_cast<float>(x) + (static_cast<float>(i) + 0.5f) / static_cast<float>(taps)) * sx;
                    const float fy = (static_cast<float>(y) + (static_cast<float>(j) + 0.5f) / static_cast<float>(taps)) * sy;
                    samplePremultiplied(image, {fx, fy}, c);
                    for (int k = 0; k < 4; ++k) acc[k] += c[k] / static_cast<float>(taps * taps);
                }
            for (int k = 0; k < 4; ++k)
                out.rgba[(static_cast<std::size_t>(y) * size + x) * 4 + k] =
                    static_cast<std::uint8_t>(std::floor(std::clamp(acc[k], 0.0f, 1.0f) * 255.0f + 0.5f));
        }
    return out;
}

void sectionMemory(const Asset& asset, Bake& bake, std::shared_ptr<const ActorTemplate> tmpl, int clip, const MorphParameters& p,
                   std::vector<Row>& rows) {
    const ImpostorAtlas& full = *bake.full;
    const int size = full.cellSize();
    // M3: every key-frame at the resolution of equal memory (half the pixels), and at half the side.
    const int equal = static_cast<int>(std::floor(size / std::sqrt(2.0)));
    struct Low {
        std::string name;
        std::unique_ptr<Bake> bake;
    };
    std::vector<Low> lows;
    for (int s : {equal, size / 2}) {
        ImpostorBakeOptions o = bake.options;
        o.cellSize = s;
        std::fprintf(stderr, "%s: [memory] baking at %d px...\n", asset.name.c_str(), s);
        lows.push_back({"", makeBake(tmpl, clip, o)});
    }
    struct Model {
        std::string name;
        int kind;  // 0 previous (M1), 1 lines (M2/M4/ours), 2 low resolution (M3), 3 proxy (ours)
        Method method;
        int low = 0;
    };
    const std::size_t all = full.boneCount();
    const std::vector<Model> models = {
        {"M1: 8 key-frames, " + std::to_string(size) + " px, in-betweens show the previous key-frame", 0, {}, 0},
        {"M2: M1's texture + 8 in-betweens morphed with 12 features", 1, linesMethod("", std::min<std::size_t>(12, all), p), 0},
        {"M3: 16 key-frames at " + std::to_string(equal) + " px (equal memory)", 2, {}, 0},
        {"M3': 16 key-frames at " + std::to_string(size / 2) + " px (half the side)", 2, {}, 1},
        {"M4: M1's texture + 8 in-betweens morphed with 8 features", 1, linesMethod("", std::min<std::size_t>(8, all), p), 0},
        {"ours: M1's texture + in-betweens morphed with all bones as capsules + depth", 1, oursLines("", all, p), 0},
        {"ours: M1's texture + in-betweens warped through the surface proxy", 3, proxyMethod(""), 0},
    };
    for (const Model& model : models) {
        Scores every, between;
        for (int k = 0; k < full.keyframeCount(); ++k)
            for (std::uint32_t v = 0; v < full.views().viewCount(); ++v) {
                const Image truth = full.cell(v, k);
                Image shown;
                if (model.kind == 2) shown = resample(lows[static_cast<std::size_t>(model.low)].bake->full->cell(v, k), size);
                else if (bake.half->stored(k)) shown = truth;
                else if (model.kind == 0) shown = bake.half->cell(v, k - 1);
                else shown = regenerate(bake, model.method, v, k, every);
                every.add(shown, truth);
                if (k % 2 == 1) between.add(shown, truth);
            }
        Row r = makeRow("memory", asset.name, full.clipName(), model.name, every);
        r.psnr = every.pooledPsnr();  // half the cells are exact for M1, M2, M4 and ours
        r.extra = mean(between.ncc);
        if (model.kind == 2) r.bytes = lows[static_cast<std::size_t>(model.low)].bake->full->textureBytes();
        else {
            r.bytes = bake.half->textureBytes();
            if (model.kind == 1) r.bytes += bake.lineBytes();
            if (model.kind == 3) r.bytes += bake.proxy(0).bytes();
        }
        r.path = model.kind == 2 ? "-" : pathOf(bake, model.method);
        rows.push_back(r);
        std::fprintf(stderr, "%s: [memory] %s: NCC %.4f (in-betweens %.4f) %.1f MiB\n", asset.name.c_str(), model.name.c_str(), r.ncc, r.extra,
                     static_cast<double>(r.bytes) / 1048576.0);
    }
}

// The stored cells that cell (`v`, `k`) of `atlas` is regenerated from (ImpostorAtlas::sources,
// up to four) as warp sources reading `images`; returns how many.
std::size_t cellProxySources(const ImpostorAtlas& atlas, std::uint32_t v, int k, std::array<Image, 4>& images,
                             std::array<ProxySource, 4>& sources) {
    const CellSources from = atlas.sources(v, k);
    for (int i = 0; i < from.count; ++i) {
        const CellSource& c = from.cells[static_cast<std::size_t>(i)];
        images[static_cast<std::size_t>(i)] = atlas.cell(c.view, c.keyframe);
        sources[static_cast<std::size_t>(i)] = {&images[static_cast<std::size_t>(i)], atlas.views().direction(c.view), c.keyframe, c.weight};
    }
    return static_cast<std::size_t>(from.count);
}

// Cell (`v`, `k`) of `half` (an atlas with cells dropped) as the run time shows it: stored, or
// warped through `proxy` from the stored cells around it; the regeneration time goes into `s`.
Image shownFromHalf(const ImpostorAtlas& half, const ProxyMesh& proxy, std::uint32_t v, int k, Scores& s) {
    if (half.cellStored(v, k)) return half.cell(v, k);
    const auto t0 = std::chrono::steady_clock::now();
    std::array<Image, 4> images;
    std::array<ProxySource, 4> sources{};
    const std::size_t n = cellProxySources(half, v, k, images, sources);
    Image out = warpProxy(proxy, std::span<const ProxySource>(sources.data(), n), half.views().direction(v), k, ourProxyOptions());
    s.morphMs += ms(std::chrono::steady_clock::now() - t0);
    ++s.morphs;
    return out;
}

// Issue 37 item 3, seed 000 §5's memory result in our terms: (a) the full atlas, (b) the half atlas
// (every other key-frame and view ring dropped, regenerated through the surface proxy), (c) the
// half atlas at twice the cell size. Every cell of every view and key-frame as shown against the
// truth rendered at twice the size (smaller cells enlarged bilinearly): what a viewer sees; and
// the dropped cells alone against the truth at their own size: how good regeneration is.
void sectionHalf(const Asset& asset, Bake& bake, std::shared_ptr<const ActorTemplate> tmpl, int clip, std::vector<Row>& rows) {
    const ImpostorAtlas& full = *bake.full;
    const int size = full.cellSize();
    ImpostorBakeOptions o = bake.options;
    o.cellSize = 2 * size;
    std::fprintf(stderr, "%s: [half] baking at %d px...\n", asset.name.c_str(), o.cellSize);
    std::unique_ptr<Bake> big = makeBake(std::move(tmpl), clip, o);
    const ImpostorAtlas& truth = *big->full;
    ImpostorAtlas half = full, halfBig = truth;
    half.drop(AtlasStorage::Half);
    halfBig.drop(AtlasStorage::Half);
    struct Model {
        std::string name;
        const ImpostorAtlas* atlas;
        const ImpostorAtlas* ownTruth;
        const ProxyMesh* proxy;
    };
    const std::vector<Model> models = {
        {"(a) full atlas, " + std::to_string(size) + " px", &full, &full, nullptr},
        {"(b) half atlas, " + std::to_string(size) + " px, regenerated through the surface proxy", &half, &full, &bake.proxy(0)},
        {"(c) half atlas, " + std::to_string(2 * size) + " px, regenerated through the surface proxy", &halfBig, &truth, &big->proxy(0)},
    };
    for (const Model& m : models) {
        Scores every, dropped;
        for (int k = 0; k < full.keyframeCount(); ++k)
            for (std::uint32_t v = 0; v < full.views().viewCount(); ++v) {
                const Image shown = m.proxy ? shownFromHalf(*m.atlas, *m.proxy, v, k, dropped) : m.atlas->cell(v, k);
                every.add(resample(shown, 2 * size), truth.cell(v, k));
                if (!half.cellStored(v, k)) dropped.add(shown, m.ownTruth->cell(v, k));  // the cells the half atlases drop
            }
        Row r = makeRow("half", asset.name, full.clipName(), m.name, every);
        r.psnr = every.pooledPsnr();
        r.extra = mean(dropped.ncc);
        r.msPerCell = dropped.msPerMorph();
        r.bytes = m.atlas->textureBytes() + (m.proxy ? m.proxy->bytes() : 0);
        char note[160];
        std::snprintf(note, sizeof note, "%.4f|%.2f|%.4f|%d", mean(dropped.ncc), dropped.pooledPsnr(), mean(dropped.ssim),
                      static_cast<int>(dropped.ncc.size()));
        r.note = note;
        r.path = m.proxy ? "CPU, 1 thread" : "-";
        rows.push_back(r);
        std::fprintf(stderr, "%s: [half] %s: %.2f MiB, shown NCC %.4f PSNR %.2f, dropped NCC %.4f\n", asset.name.c_str(), m.name.c_str(),
                     static_cast<double>(r.bytes) / 1048576.0, r.ncc, r.psnr, r.extra);
    }
}

// Issue 37's acceptance in throng-town's terms: the scene's templates baked exactly as throng-town
// bakes them (apps/support's sceneBakeOptions: 64 px cells, the scene's atlas storage, the main
// clip of each), every view of every dropped cell made as the run time makes it (makeDroppedCell:
// the renderer's own CPU path; GpuProxyWarper: the GL's) against the truly rendered cell, and the
// GL's cells against the CPU's, pixel by pixel. The feature-line morph (--cell-warp lines, the run
// time before the surface proxy) beside them. Templates with looks are measured as shown (wearing
// them), and their CPU cells also as the atlas holds them (every region white): a harder measure,
// with less texture to correlate.
void sectionRuntime(const std::string& sceneFile, std::vector<Row>& rows) {
    sim::SceneDescription description = sim::parseSceneFile(sceneFile);
    std::fprintf(stderr, "[runtime] building the world of %s...\n", sceneFile.c_str());
    const std::unique_ptr<sim::Simulation> world = sim::Simulation::build(std::move(description));
    const ImpostorBakeOptions options = support::sceneBakeOptions(*world);
    for (const sim::Simulation::TemplateInUse& t : world->templates()) {
        // A template with looks is baked white per region and shown wearing them: measured as shown,
        // each cell (the truth and every regenerated one alike) wearing the template's looks in
        // turn, through the true cell's regions, as the impostor passes draw it (applyBodyLook).
        const std::string key = t.name.substr(0, t.name.find('#'));
        const auto declared = world->description().templates.find(key);
        const std::vector<BodyLook> looks = declared != world->description().templates.end() ? declared->second.looks : std::vector<BodyLook>{};
        std::fprintf(stderr, "[runtime] %s: baking as throng-town does (%d px)...\n", t.name.c_str(), options.cellSize);
        auto context = createContext({.width = options.cellSize, .height = options.cellSize, .api = bakeGl});
        ImpostorBaker baker(context, t.tmpl, t.clip, options);
        const ImpostorAtlas full = baker.bake();
        ImpostorAtlas stored = full;
        stored.setProxy(std::make_shared<const ProxyMesh>(baker.proxyMesh()));
        stored.drop(options.storage);
        GpuProxyWarper gl(context);
        ImpostorRendererOptions proxy, lines;  // throng-town's defaults: --morph background, --cell-warp proxy or lines
        lines.warp = CellWarp::FeatureLines;
        Scores onCpu, onGl, byLines, baked;  // baked: the CPU's cells as the atlas holds them (white regions), with looks
        std::size_t differing = 0, pixels = 0;
        int largest = 0;
        for (int k = 0; k < full.keyframeCount(); ++k)
            for (std::uint32_t v = 0; v < full.views().viewCount(); ++v) {
                if (stored.cellStored(v, k)) continue;
                const BodyLook* look = full.hasRegions() && !looks.empty() ? &looks[(static_cast<std::size_t>(k) * full.views().viewCount() + v) % looks.size()] : nullptr;
                const auto asShown = [&](const Image& cell) { return look ? applyBodyLook(cell, full.regions(v, k), *look) : cell; };
                const Image truth = asShown(full.cell(v, k));
                auto t0 = std::chrono::steady_clock::now();
                Image cpu = makeDroppedCell(stored, v, k, proxy);
                onCpu.morphMs += ms(std::chrono::steady_clock::now() - t0), ++onCpu.morphs;
                if (look) baked.add(cpu, full.cell(v, k)), baked.morphMs = onCpu.morphMs, baked.morphs = onCpu.morphs;
                cpu = asShown(cpu);
                std::array<Image, 4> images;
                std::array<ProxySource, 4> sources{};
                const std::size_t n = cellProxySources(stored, v, k, images, sources);
                ProxyWarpOptions warp;
                warp.opaqueInside = true;  // as the renderer warps
                t0 = std::chrono::steady_clock::now();
                Image fromGl = gl.warp(*stored.proxy(), std::span<const ProxySource>(sources.data(), n), stored.views().direction(v), k, warp);
                onGl.morphMs += ms(std::chrono::steady_clock::now() - t0), ++onGl.morphs;
                fromGl = asShown(fromGl);
                t0 = std::chrono::steady_clock::now();
                Image byLine = makeDroppedCell(stored, v, k, lines);
                byLines.morphMs += ms(std::chrono::steady_clock::now() - t0), ++byLines.morphs;
                byLine = asShown(byLine);
                onCpu.add(cpu, truth);
                onGl.add(fromGl, truth);
                byLines.add(byLine, truth);
                const testkit::ImageDifference d = testkit::compareImages(cpu, fromGl, 2);
                differing += d.pixelsOverThreshold;
                pixels += static_cast<std::size_t>(cpu.width) * static_cast<std::size_t>(cpu.height);
                largest = std::max(largest, d.maxChannelDifference);
            }
        const std::string clip = full.clipName();
        char note[160];
        std::snprintf(note, sizeof note, "GL against CPU: %zu of %zu pixels differ by more than 2/255 (%.4f %%), largest difference %d/255",
                      differing, pixels, pixels ? 100.0 * static_cast<double>(differing) / static_cast<double>(pixels) : 0.0, largest);
        for (auto [name, scores, path] : {std::tuple{"surface proxy, CPU (throng-town's default)", &onCpu, "CPU, 1 thread"},
                                          std::tuple{"surface proxy, GL (--morph gl)", &onGl, "GL, read back"},
                                          std::tuple{"feature lines (--cell-warp lines)", &byLines, "CPU, 4 px grid"},
                                          std::tuple{"white-baked cells, surface proxy CPU", &baked, "CPU, 1 thread"}}) {
            if (scores->ncc.empty()) continue;  // no looks: no white-baked cells
            Row r = makeRow("runtime", t.name, clip, name, *scores);
            r.path = path;
            r.bytes = stored.textureBytes();
            r.extra = scores->ncc.empty() ? 0.0 : *std::min_element(scores->ncc.begin(), scores->ncc.end());
            if (scores == &onGl) r.note = note;
            if (!looks.empty() && full.hasRegions()) r.note += std::string(r.note.empty() ? "" : "; ") + "wearing the scene's " + std::to_string(looks.size()) + " looks";
            rows.push_back(r);
        }
        std::fprintf(stderr, "[runtime] %s: %zu dropped cells, NCC proxy CPU %.4f GL %.4f lines %.4f, white-baked cells %.4f; %s\n", t.name.c_str(),
                     onCpu.ncc.size(), mean(onCpu.ncc), mean(onGl.ncc), mean(byLines.ncc), baked.ncc.empty() ? 0.0 : mean(baked.ncc), note);
    }
}

// The knob sweep: each configuration baked, every dropped cell regenerated ("dropped": against the
// truth at that configuration), and random eye directions and clip times shown as the run time
// shows them ("shown": the key-frame at or before the time, morphed if dropped, in the colour
// blend of three views; or warped through the proxy straight to that time and direction), against
// the cell rendered at that very time and direction at twice the reference size, shrunk to it).
void sectionSweep(const Asset& asset, std::shared_ptr<const ActorTemplate> tmpl, int clip, const ImpostorBakeOptions& reference, Bake& base,
                  const MorphParameters& p, const std::set<std::string>& knobs, std::vector<AccuracyRow>& rows) {
    const std::string scene = asset.name + "/" + base.full->clipName();
    struct Config {
        std::string knob, value;
        ImpostorBakeOptions options;
    };
    std::vector<Config> configs;
    for (int s : {64, 96, 128, 192, 256}) {
        ImpostorBakeOptions o = reference;
        o.cellSize = s;
        configs.push_back({"cell_size", std::to_string(s), o});
    }
    for (auto [az, el] : {std::pair{8, 2}, {12, 3}, {16, 4}, {24, 6}}) {
        ImpostorBakeOptions o = reference;
        o.azimuths = az, o.elevations = el;
        configs.push_back({"views", std::to_string(az) + "x" + std::to_string(el), o});
    }
    for (int kept : {4, 8, 16}) {
        ImpostorBakeOptions o = reference;
        o.keyframes = 2 * kept;
        configs.push_back({"keyframes_kept", std::to_string(kept), o});
    }
    const std::size_t all = base.half->boneCount();
    Method direct = proxyMethod("surface proxy, straight to the eye and time");
    direct.direct = true;
    Method direct4 = proxyMethod("surface proxy (4 poses per key-frame), straight to the eye and time");
    direct4.direct = true;
    direct4.proxySamples = 4;
    std::vector<std::pair<std::string, Method>> featureMethods = {
        {"0", linesMethod("cross-dissolve", 0, p)},
        {"4", linesMethod("morph, strongest bones", std::min<std::size_t>(4, all), p)},
        {"8", linesMethod("morph, strongest bones", std::min<std::size_t>(8, all), p)},
        {"12", linesMethod("morph, strongest bones", std::min<std::size_t>(12, all), p)},
        {"all", linesMethod("morph, all bones", all, p)},
        {"all_capsules_depth", oursLines("morph, all bones as capsules + depth order", all, p)},
        {"surface_proxy", proxyMethod("surface-proxy warp")},
        {"surface_proxy_direct", direct},
        {"surface_proxy_direct_4_poses", direct4},
    };
    // Samples shared by every row.
    std::mt19937 rng(11);
    const ViewHemisphere refViews(reference.azimuths, reference.elevations);
    std::uniform_real_distribution<float> az(0.0f, 6.2831853f), el(0.0f, refViews.elevation(refViews.elevations() - 1)), phase(0.0f, 1.0f);
    struct Sample {
        glm::vec3 dir;
        double phase;
        Image truth;
    };
    // The truth: rendered at twice the reference size and shrunk with the area filter, so every
    // cell size is measured against the same well-filtered image rather than one of them.
    ImpostorBakeOptions fine = reference;
    fine.cellSize = 2 * reference.cellSize;
    auto fineContext = createContext({.width = fine.cellSize, .height = fine.cellSize, .api = bakeGl});
    ImpostorBaker fineBaker(fineContext, tmpl, clip, fine);
    std::vector<Sample> samples;
    for (int i = 0; i < 48; ++i) {
        const float a = az(rng), e = el(rng);
        const glm::vec3 dir(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
        const double ph = phase(rng);
        samples.push_back({dir, ph, resample(fineBaker.renderCell(ph * base.full->duration(), dir), reference.cellSize)});
    }
    const auto measure = [&](const std::string& knob, const std::string& value, Bake& bake, const Method& m) {
        const std::size_t bytes = bake.half->textureBytes() +
                                  (m.kind == Method::Kind::Proxy ? bake.proxy(m.proxyBudget, m.proxySamples).bytes() : bake.lineBytes());
        AccuracyRow d{knob, value, m.name, scene, "dropped_cells"};
        if (!m.direct) {
            // Dropped cells at this configuration.
            const Row dropped = measureDropped("sweep", asset, bake, m, false);
            d.ncc = dropped.ncc, d.nccStd = dropped.nccStd, d.nccWhole = dropped.nccWhole, d.psnr = dropped.psnr, d.ssim = dropped.ssim;
            d.msPerCell = dropped.msPerCell, d.samples = dropped.cells, d.bytes = bytes;
            rows.push_back(d);
        }
        // Shown at random eye directions and times.
        Scores s;
        std::map<std::pair<std::uint32_t, int>, Image> morphed;
        const ImpostorAtlas& half = *bake.half;
        for (const Sample& sample : samples) {
            if (m.direct) {
                // The stored key-frames around the time, the three views around the eye: six cells
                // warped through the proxy to that very time and direction.
                const double at = sample.phase * half.keyframeCount();
                int s0 = static_cast<int>(at);
                while (!half.stored(s0)) s0 = (s0 - 1 + half.keyframeCount()) % half.keyframeCount();
                int s1 = (s0 + 1) % half.keyframeCount();
                while (!half.stored(s1)) s1 = (s1 + 1) % half.keyframeCount();
                const double span = s1 > s0 ? s1 - s0 : s1 + half.keyframeCount() - s0;
                double f = at - s0;
                if (f < 0) f += half.keyframeCount();
                const auto w1 = static_cast<float>(f / span);
                const ViewBlend b = half.views().blend(sample.dir, false);
                std::vector<Image> cells;
                std::vector<ProxySource> sources;
                cells.reserve(6);
                for (int key : {s0, s1})
                    for (int i = 0; i < 3; ++i) cells.push_back(half.cell(b.views[static_cast<std::size_t>(i)], key));
                for (int j = 0; j < 6; ++j) {
                    const float w = b.weights[static_cast<std::size_t>(j % 3)] * (j < 3 ? 1.0f - w1 : w1);
                    if (w > 0.0f)
                        sources.push_back({&cells[static_cast<std::size_t>(j)], half.views().direction(b.views[static_cast<std::size_t>(j % 3)]),
                                           (j < 3 ? s0 : s1) * m.proxySamples, w});
                }
                const auto t0 = std::chrono::steady_clock::now();
                const Image warped = warpProxy(bake.proxy(m.proxyBudget, m.proxySamples), sources, sample.dir, at * m.proxySamples, m.proxyOptions);
                s.morphMs += ms(std::chrono::steady_clock::now() - t0);
                ++s.morphs;
                s.add(resample(warped, reference.cellSize), sample.truth);
                continue;
            }
            const int k = std::min(static_cast<int>(sample.phase * half.keyframeCount()), half.keyframeCount() - 1);
            const ViewBlend b = half.views().blend(sample.dir, false);
            std::vector<Image> cells;
            for (int i = 0; i < 3; ++i) {
                const std::uint32_t v = b.views[static_cast<std::size_t>(i)];
                if (half.stored(k)) cells.push_back(half.cell(v, k));
                else {
                    auto it = morphed.find({v, k});
                    if (it == morphed.end()) it = morphed.emplace(std::pair{v, k}, regenerate(bake, m, v, k, s)).first;
                    cells.push_back(it->second);
                }
            }
            s.add(resample(blendCells(cells, b.weights), reference.cellSize), sample.truth);
        }
        AccuracyRow r{knob, value, m.name, scene, "shown_random_eye_and_time"};
        r.ncc = mean(s.ncc), r.nccStd = stdev(s.ncc), r.nccWhole = mean(s.nccWhole), r.psnr = mean(s.psnr), r.ssim = mean(s.ssim);
        r.msPerCell = s.msPerMorph(), r.samples = static_cast<int>(s.ncc.size()), r.bytes = bytes;
        rows.push_back(r);
        std::fprintf(stderr, "%s: [sweep] %s=%s %s: dropped NCC %s, shown NCC %.4f, %.2f ms/cell, %.1f MiB\n", asset.name.c_str(), knob.c_str(),
                     value.c_str(), m.name.c_str(), m.direct ? "-" : std::to_string(d.ncc).substr(0, 6).c_str(), r.ncc, m.direct ? r.msPerCell : d.msPerCell, static_cast<double>(bytes) / 1048576.0);
    };
    const Method classic = linesMethod("morph, all bones", all, p), proxy = proxyMethod("surface-proxy warp");
    for (const Config& c : configs) {
        if (!knobs.count(c.knob)) continue;
        std::fprintf(stderr, "%s: [sweep] baking %s = %s...\n", asset.name.c_str(), c.knob.c_str(), c.value.c_str());
        const bool isBase = c.options.cellSize == reference.cellSize && c.options.azimuths == reference.azimuths &&
                            c.options.elevations == reference.elevations && c.options.keyframes == reference.keyframes;
        std::unique_ptr<Bake> own = isBase ? nullptr : makeBake(tmpl, clip, c.options);
        Bake& bake = isBase ? base : *own;
        measure(c.knob, c.value, bake, classic);
        measure(c.knob, c.value, bake, proxy);
        measure(c.knob, c.value, bake, direct);
        measure(c.knob, c.value, bake, direct4);
    }
    if (knobs.count("features"))
        for (const auto& [value, m] : featureMethods) measure("features", value, base, m);
}

// The common accuracy CSV: the knob sweeps (one knob per sweep and method; the measure, dropped
// cells at the baked views or cells shown at random eyes and times, as the camera), the view blends,
// Table 2 and the equal-memory models. Time: milliseconds to make one cell (or image) on its path.
void writeAccuracyCsv(const std::string& path, const std::vector<AccuracyRow>& sweep, const std::vector<Row>& rows,
                      const ImpostorBakeOptions& reference) {
    // The scene names the bake every knob is varied around.
    const std::string bake = ", " + std::to_string(reference.cellSize) + " px, " + std::to_string(reference.azimuths) + "x" +
                             std::to_string(reference.elevations) + " views, " + std::to_string(reference.keyframes) + " key-frames";
    sim::AccuracyCsv csv(path);
    const auto record = [&](std::string knob, std::string value, std::string scene, std::string camera, double ncc, double nccWhole,
                            double psnr, double ssim, double msPerCell, double bytes) {
        sim::AccuracyRecord a;
        a.knob = std::move(knob);
        a.value = std::move(value);
        a.metrics = {{"ncc", ncc, "1", false}, {"ncc_whole_cell", nccWhole, "1", false}, {"psnr", psnr, "dB", false}, {"ssim", ssim, "1", false}};
        a.ms = msPerCell;
        a.msPhase = "per_cell";
        a.memoryBytes = bytes;
        a.scene = std::move(scene) + bake;
        a.camera = std::move(camera);
        a.actors = 1;
        csv.add(a);
    };
    for (const AccuracyRow& r : sweep) {
        std::string knob = r.knob;
        std::replace(knob.begin(), knob.end(), '_', ' ');
        record("impostor " + knob + (r.knob == "features" ? std::string() : ", " + r.method), r.knob == "features" ? r.value + " (" + r.method + ")" : r.value,
               r.scene, r.measure == "dropped_cells" ? "baked views" : "random eyes", r.ncc, r.nccWhole, r.psnr, r.ssim, r.msPerCell,
               static_cast<double>(r.bytes));
    }
    for (const Row& r : rows) {
        const char* knob = r.section == "views" ? "impostor view blending" : r.section == "table2" ? "impostor seed 000 table 2"
                         : r.section == "memory" ? "impostor equal memory model"
                         : r.section == "half"   ? "impostor atlas storage"
                         : r.section == "runtime" ? "impostor run-time regeneration"
                                                 : nullptr;
        if (!knob) continue;
        record(knob, r.method, r.asset + "/" + r.clip, r.section == "views" ? "random eyes" : "baked views", r.ncc, r.nccWhole, r.psnr, r.ssim,
               r.msPerCell, static_cast<double>(r.bytes));
    }
}

// ------------------------------------------------------------------------------------------------
// Report.

std::string fmtMs(const Row& r) {
    if (r.path == "-" || r.msPerCell <= 0) return "-";
    char b[32];
    std::snprintf(b, sizeof b, "%.2f", r.msPerCell);
    return b;
}

void writeTable(std::ostringstream& md, const std::vector<Row>& rows, const std::string& section) {
    char line[768];
    md << "| asset | method | features | NCC | NCC std | NCC whole cell | PSNR dB | SSIM | ms/cell | path |\n"
          "|---|---|---:|---:|---:|---:|---:|---:|---:|---|\n";
    for (const Row& r : rows) {
        if (r.section != section) continue;
        std::snprintf(line, sizeof line, "| %s | %s | %s | %.4f | %.4f | %.4f | %.2f | %.4f | %s | %s |\n", r.asset.c_str(), r.method.c_str(),
                      r.features < 0 ? "-" : std::to_string(r.features).c_str(), r.ncc, r.nccStd, r.nccWhole, r.psnr, r.ssim, fmtMs(r).c_str(),
                      r.path.empty() ? "-" : r.path.c_str());
        md << line;
    }
}

}  // namespace

int main(int argc, char** argv) {
    std::filesystem::path out = "impostor-report";
    ImpostorBakeOptions options;
    MorphParameters parameters;
    std::vector<Asset> assets;
    const std::string shared = testkit::sharedAssets();
    std::string outText = out.string();
    support::ViewGrid views{options.azimuths, options.elevations};
    std::vector<std::string> assetTexts, sectionTexts;
    support::CommandLine cl("throng-impostor-quality",
                            "How good regenerated impostor cells are and what they cost: NCC, PSNR and SSIM of morphed\n"
                            "and warped against truly rendered cells, texture memory, morph time, view blending and\n"
                            "warping, seed 000's Table 2 and equal-memory comparison, and knob sweeps. Writes\n"
                            "impostor-quality.md, impostor-quality.csv, impostor-accuracy.csv and impostor-quality.png\n"
                            "(the plot through VTK: without a display, run under xvfb-run -a).");
    CLI::App& app = cl.app();
    app.add_option("--out", outText, "folder for the report")->type_name("DIR")->check(support::folderToWrite());
    app.add_option("--size", options.cellSize, "cell side")->type_name("PIXELS")->check(support::wholeNumber(8, 4096));
    app.add_option("--keyframes", options.keyframes, "key-frames over the clip (odd ones are dropped and regenerated)")
        ->type_name("N")
        ->check(support::wholeNumber(4, 1024));
    app.add_option("--views", views, "azimuths x elevations on the hemisphere")->type_name("AxE")->check(support::viewGrid());
    app.add_option("--a", parameters.a, "Beier-Neely a, pixels")->type_name("X")->check(support::nonNegativeNumber());
    app.add_option("--b", parameters.b, "Beier-Neely b: how fast weight falls with distance")
        ->type_name("X")
        ->check(support::nonNegativeNumber());
    app.add_option("--p", parameters.p, "Beier-Neely p: how much longer lines weigh more")
        ->type_name("X")
        ->check(support::nonNegativeNumber());
    app.add_option("--asset", assetTexts, "a character to measure, once per character (SOURCE: a file or seed-humanoid)")
        ->type_name("NAME=SOURCE:CLIP")
        ->check(assetValidator())
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
        ->allow_extra_args(false)
        ->default_str("CesiumMan, robot and Fox");
    app.add_option("--sections", sectionTexts, "sections to run, comma-separated")
        ->type_name("LIST")
        ->delimiter(',')
        ->check(support::oneOf(kSections))
        ->default_str("morph,features,abp,views,table2,memory,half,sweep,runtime");
    std::string sceneFile = testkit::townDefaultScene();
    app.add_option("--scene", sceneFile, "the scene the runtime section bakes and measures as throng-town does")
        ->type_name("FILE")
        ->check(CLI::ExistingFile)
        ->default_str("throng-town's default scene");
    const std::vector<std::string> kSweepKnobs = {"cell_size", "views", "keyframes_kept", "features"};
    std::vector<std::string> sweepKnobTexts;
    app.add_option("--sweep-knobs", sweepKnobTexts, "knobs the sweep section measures, comma-separated (fewer: a shorter run)")
        ->type_name("LIST")
        ->delimiter(',')
        ->check(support::oneOf(kSweepKnobs))
        ->default_str("cell_size,views,keyframes_kept,features");
    std::string gl = "auto";
    support::declareGlOption(app, gl, false);
    if (const auto code = cl.parse(argc, argv)) return *code;
    if (const auto code = support::refuseUnavailableGl("throng-impostor-quality", gl)) return *code;
    bakeGl = glApiFromName(gl);
    const std::set<std::string> sweepKnobs = sweepKnobTexts.empty() ? std::set<std::string>(kSweepKnobs.begin(), kSweepKnobs.end())
                                                                    : std::set<std::string>(sweepKnobTexts.begin(), sweepKnobTexts.end());
    out = outText;
    options.azimuths = views.azimuths;
    options.elevations = views.elevations;
    for (const std::string& text : assetTexts) assets.push_back(*parseAsset(text));
    const std::set<std::string> sections = sectionTexts.empty() ? std::set<std::string>(kSections.begin(), kSections.end())
                                                                : std::set<std::string>(sectionTexts.begin(), sectionTexts.end());
    const auto wants = [&](const char* s) { return sections.count(s) > 0; };
    try {
        if (assets.empty())
            assets = {{"CesiumMan", shared + "/characters/CesiumMan.glb", ""},
                      {"robot", shared + "/characters/robot.glb", "Robot_Walking"},
                      {"Fox", shared + "/characters/Fox.glb", "Walk"}};
        std::filesystem::create_directories(out);
        const auto started = std::chrono::steady_clock::now();
        std::vector<Row> rows;
        std::vector<AccuracyRow> accuracy;
        struct Memory {
            std::string asset;
            std::size_t full = 0, half = 0, lines = 0, track = 0, proxy = 0;
            int proxyVertices = 0;
        };
        std::vector<Memory> memory;
        const bool perAsset = std::any_of(sections.begin(), sections.end(), [](const std::string& s) { return s != "runtime"; });
        for (const Asset& a : (perAsset ? assets : std::vector<Asset>{})) {
            const auto tmpl = support::loadTemplate(a.source);
            const int clip = support::findClipOrThrow(*tmpl, a.clip);
            std::fprintf(stderr, "%s: baking...\n", a.name.c_str());
            std::unique_ptr<Bake> bake = makeBake(tmpl, clip, options);
            memory.push_back({a.name, bake->full->textureBytes(), bake->half->textureBytes(), bake->lineBytes(), bake->track->bytes(),
                              bake->proxy(0).bytes(), static_cast<int>(bake->proxy(0).vertexCount())});
            if (wants("morph")) sectionMorph(a, *bake, parameters, out, rows);
            if (wants("features")) sectionFeatures(a, *bake, parameters, rows);
            if (wants("abp")) sectionAbp(a, *bake, parameters, rows);
            if (wants("views")) sectionViews(a, *bake, parameters, rows);
            if (wants("table2")) sectionTable2(a, *bake, parameters, rows);
            if (wants("memory")) sectionMemory(a, *bake, tmpl, clip, parameters, rows);
            if (wants("half")) sectionHalf(a, *bake, tmpl, clip, rows);
            if (wants("sweep")) sectionSweep(a, tmpl, clip, options, *bake, parameters, sweepKnobs, accuracy);
        }
        if (wants("runtime")) sectionRuntime(sceneFile, rows);
        const double minutes = ms(std::chrono::steady_clock::now() - started) / 60000.0;

        std::ostringstream csv;
        csv << "section,asset,clip,method,features,ncc_mean,ncc_std,ncc_whole_cell,ncc_whole_cell_std,psnr_db,ssim,cells,ms_per_cell,path,memory_bytes,"
               "ncc_in_betweens\n";
        for (const Row& r : rows)
            csv << r.section << ',' << r.asset << ',' << r.clip << ",\"" << r.method << "\"," << r.features << ',' << r.ncc << ',' << r.nccStd << ','
                << r.nccWhole << ',' << r.nccWholeStd << ',' << r.psnr << ',' << r.ssim << ',' << r.cells << ',' << r.msPerCell << ",\"" << r.path
                << "\"," << r.bytes << ',' << r.extra << '\n';
        writeWholeFile(out / "impostor-quality.csv", csv.str());
        writeAccuracyCsv((out / "impostor-accuracy.csv").string(), accuracy, rows, options);

        std::ostringstream md;
        char line[768];
        md << "# Impostor morphing: quality and cost\n\n";
        md << "Cells of " << options.cellSize << " px, " << options.azimuths << " x " << options.elevations << " views, " << options.keyframes
           << " key-frames, Beier-Neely a = " << parameters.a << " px, b = " << parameters.b << ", p = " << parameters.p
           << "; odd key-frames dropped and regenerated; every view of every dropped key-frame compared with the truly rendered cell. "
              "NCC: Pearson correlation over the pixels either image covers; NCC whole cell: over the entire cell. ms/cell: "
              "wall time to regenerate one cell on the path shown (GPU: the fragment-shader morph, llvmpipe here). "
              "Run took "
           << static_cast<int>(std::ceil(minutes)) << " min.\n\n";
        if (wants("morph")) {
            md << "## Dropped key-frames\n\n";
            writeTable(md, rows, "morph");
        }
        md << "\n| asset | texture, all key-frames | texture, half | ratio | bone lines | 3-D bones | surface proxy (vertices) | half + proxy |\n"
              "|---|---:|---:|---:|---:|---:|---:|---:|\n";
        for (const Memory& m : memory) {
            std::snprintf(line, sizeof line, "| %s | %.2f MiB | %.2f MiB | %.1f%% | %.1f KiB | %.1f KiB | %.1f KiB (%d) | %.1f%% |\n", m.asset.c_str(),
                          static_cast<double>(m.full) / 1048576.0, static_cast<double>(m.half) / 1048576.0,
                          100.0 * static_cast<double>(m.half) / static_cast<double>(m.full), static_cast<double>(m.lines) / 1024.0,
                          static_cast<double>(m.track) / 1024.0, static_cast<double>(m.proxy) / 1024.0, m.proxyVertices,
                          100.0 * static_cast<double>(m.half + m.proxy) / static_cast<double>(m.full));
            md << line;
        }
        if (wants("features")) {
            md << "\n## Automatic features\n\nEvery row regenerates the same dropped cells; \"bound\" rows use the truth and are not "
                  "methods.\n\n";
            writeTable(md, rows, "features");
        }
        if (wants("abp")) {
            md << "\n## Beier-Neely a, b, p (one at a time around the defaults)\n\n";
            writeTable(md, rows, "abp");
        }
        if (wants("views")) {
            md << "\n## Between the baked views\n\n96 random eye directions (stored key-frames), against the cell rendered from "
                  "that direction; the colour blends and warps use the three views of the grid triangle around the eye "
                  "with their barycentric weights.\n\n";
            writeTable(md, rows, "views");
        }
        if (wants("table2")) {
            md << "\n## Seed 000 Table 2 on our characters\n\nKey-frames: every view of every dropped key-frame. View-points: every "
                  "odd azimuth of every stored key-frame, regenerated from its two azimuth neighbours (a grid of half the "
                  "azimuths); (8) and (12) use seed 000's view morphing with the strongest bones. Cons.: the previous "
                  "key-frame or azimuth itself.\n\n| asset | target images (features) | CC mean | CC std | CC whole cell | CC whole "
                  "cell std | PSNR dB | SSIM |\n|---|---|---:|---:|---:|---:|---:|---:|\n";
            for (const Row& r : rows)
                if (r.section == "table2") {
                    std::snprintf(line, sizeof line, "| %s | %s | %.2f | %.2f | %.2f | %.2f | %.2f | %.3f |\n", r.asset.c_str(), r.method.c_str(), r.ncc,
                                  r.nccStd, r.nccWhole, r.nccWholeStd, r.psnr, r.ssim);
                    md << line;
                }
        }
        if (wants("memory")) {
            md << "\n## Equal memory (seed 000 §6.2, models M1-M4)\n\nEvery view of all " << options.keyframes
               << " key-frames against the truly rendered cell at " << options.cellSize
               << " px (lower resolutions upsampled bilinearly). Memory: texture plus the features each model reads. PSNR: of the "
                  "mean squared error over all cells (the stored key-frames are exact).\n\n"
                  "| asset | model | memory | NCC | NCC in-betweens | NCC whole cell | PSNR dB | SSIM | ms/cell |\n"
                  "|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
            for (const Row& r : rows)
                if (r.section == "memory") {
                    std::snprintf(line, sizeof line, "| %s | %s | %.2f MiB | %.4f | %.4f | %.4f | %.2f | %.4f | %s |\n", r.asset.c_str(), r.method.c_str(),
                                  static_cast<double>(r.bytes) / 1048576.0, r.ncc, r.extra, r.nccWhole, r.psnr, r.ssim, fmtMs(r).c_str());
                    md << line;
                }
        }
        if (wants("runtime")) {
            md << "\n## At run time, in a scene (" << std::filesystem::path(sceneFile).filename().string()
               << ")\n\nEach template baked as throng-town bakes it (64 px cells, its main clip, the scene's atlas storage), "
                  "every view of every dropped cell made as the run time makes it, against the truly rendered cell. NCC min: the "
                  "worst cell.\n\n| template | clip | method | NCC | NCC min | NCC whole cell | PSNR dB | SSIM | cells | ms/cell | note |\n"
                  "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---|\n";
            for (const Row& r : rows)
                if (r.section == "runtime") {
                    std::snprintf(line, sizeof line, "| %s | %s | %s | %.4f | %.4f | %.4f | %.2f | %.4f | %d | %s | %s |\n", r.asset.c_str(), r.clip.c_str(),
                                  r.method.c_str(), r.ncc, r.extra, r.nccWhole, r.psnr, r.ssim, r.cells, fmtMs(r).c_str(), r.note.c_str());
                    md << line;
                }
        }
        if (wants("half")) {
            md << "\n## Half the atlas (seed 000 §5)\n\nThe half atlas keeps every other key-frame and every other view ring (of "
               << options.elevations << ": the horizon's and every second one up) and regenerates the rest when drawn, each cell through "
                  "the surface proxy from the stored cells around it (the key-frames before and after, the rings below and above, up to "
                  "four). Shown: every cell of every view and key-frame as drawn, against the truth rendered at "
               << 2 * options.cellSize << " px (smaller cells enlarged bilinearly). Dropped: the cells the half atlas drops, against "
                  "the truth at their own size. Memory: texture plus the surface proxy.\n\n"
                  "| asset | atlas | memory | of (a) | shown NCC | shown PSNR dB | shown SSIM | dropped NCC | dropped PSNR dB | dropped SSIM "
                  "| dropped cells | ms/cell |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
            std::size_t fullBytes = 1;
            for (const Row& r : rows)
                if (r.section == "half") {
                    if (r.method.rfind("(a)", 0) == 0) fullBytes = r.bytes;
                    std::string cells[4] = {"-", "-", "-", "-"};
                    std::istringstream parts(r.note);
                    for (std::string& c : cells) std::getline(parts, c, '|');
                    const bool none = r.path == "-";  // the full atlas shows stored cells only
                    std::snprintf(line, sizeof line, "| %s | %s | %.2f MiB | %.0f%% | %.4f | %.2f | %.4f | %s | %s | %s | %s | %s |\n", r.asset.c_str(),
                                  r.method.c_str(), static_cast<double>(r.bytes) / 1048576.0,
                                  100.0 * static_cast<double>(r.bytes) / static_cast<double>(fullBytes), r.ncc, r.psnr, r.ssim,
                                  none ? "exact" : cells[0].c_str(), none ? "exact" : cells[1].c_str(), none ? "exact" : cells[2].c_str(),
                                  cells[3].c_str(), none ? "-" : fmtMs(r).c_str());
                    md << line;
                }
        }
        if (wants("sweep")) {
            md << "\n## Knobs (impostor-accuracy.csv)\n\n\"dropped\": every dropped cell of that configuration against its truth; "
                  "\"shown\": 48 random eye directions and clip times shown as the run time shows them (key-frame at or before "
                  "the time, morphed if dropped, colour blend of three views) against the cell rendered there at "
                  << 2 * options.cellSize << " px and shrunk to " << options.cellSize
                  << " px (every cell size resampled to that); \"straight to the eye and time\" instead warps the six stored cells around the time and the eye "
                     "through the proxy to that very time and direction (per actor: nothing shared; its ms are per image).\n\n| scene | knob | value | method | dropped NCC | dropped PSNR | dropped SSIM | shown NCC | shown PSNR "
                     "| shown SSIM | morph ms/cell | memory |\n|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
            for (std::size_t i = 0; i < accuracy.size(); ++i) {
                const AccuracyRow& s = accuracy[i];
                if (s.measure != "shown_random_eye_and_time") continue;
                const AccuracyRow* d = i > 0 && accuracy[i - 1].measure == "dropped_cells" && accuracy[i - 1].method == s.method ? &accuracy[i - 1] : nullptr;
                char dropped[96] = "| - | - | -";
                if (d) std::snprintf(dropped, sizeof dropped, "| %.4f | %.2f | %.4f", d->ncc, d->psnr, d->ssim);
                std::snprintf(line, sizeof line, "| %s | %s | %s | %s %s | %.4f | %.2f | %.4f | %.2f | %.2f MiB |\n", s.scene.c_str(), s.knob.c_str(),
                              s.value.c_str(), s.method.c_str(), dropped, s.ncc, s.psnr, s.ssim, d ? d->msPerCell : s.msPerCell,
                              static_cast<double>(s.bytes) / 1048576.0);
                md << line;
            }
        }
        writeWholeFile(out / "impostor-quality.md", md.str());
        std::printf("%s", md.str().c_str());

        // The plot: NCC against feature count per asset (bone lines), with the baselines and the
        // surface proxy as horizontal lines.
        if (wants("morph")) {
            vtk::Chart chart;
            chart.title = "Regenerated impostor key-frames against truly rendered ones";
            chart.xLabel = "feature lines (bones)";
            chart.yLabel = "mean NCC";
            chart.legend = vtk::Chart::Legend::Bottom;
            int colour = 0;
            for (const Asset& a : assets) {
                vtk::ChartSeries morph, prev, proxy;
                morph.name = a.name + ": morph, bone lines";
                prev.name = a.name + ": previous key-frame";
                proxy.name = a.name + ": surface proxy";
                morph.style = vtk::ChartSeries::Style::LineAndPoints;
                prev.style = vtk::ChartSeries::Style::DashedLine;
                proxy.style = vtk::ChartSeries::Style::Line;
                vtk::paletteColour(colour, morph.rgb);
                vtk::paletteColour(colour, prev.rgb);
                vtk::paletteColour(colour++, proxy.rgb);
                double baseline = 0, surface = 0;
                for (const Row& r : rows) {
                    if (r.asset != a.name || r.section != "morph") continue;
                    if (r.features < 0) baseline = r.ncc;
                    else if (r.method.rfind("surface", 0) == 0) surface = r.ncc;
                    else if (r.method.rfind("morph, strongest", 0) == 0 || r.method == "morph, all bones" || r.method == "cross-dissolve")
                        morph.x.push_back(r.features), morph.y.push_back(r.ncc);
                }
                if (morph.x.empty()) continue;
                prev.x = proxy.x = {morph.x.front(), morph.x.back()};
                prev.y = {baseline, baseline};
                proxy.y = {surface, surface};
                chart.series.push_back(morph);
                chart.series.push_back(prev);
                chart.series.push_back(proxy);
            }
            try {
                if (!chart.series.empty()) vtk::writeChartPng(chart, (out / "impostor-quality.png").string());
            } catch (const std::exception& e) {
                std::fprintf(stderr, "no plot (%s)\n", e.what());
            }
        }
        std::fprintf(stderr, "written to %s in %.1f min\n", out.c_str(), minutes);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "throng-impostor-quality: %s\n", e.what());
        return 1;
    }
}
