// throng-impostor-quality: how good morphed impostor key-frames are, and what they cost (DESIGN.md,
// "Accuracy costs time: show both"). For each character and clip: bakes every key-frame, drops
// the odd ones, regenerates each dropped cell (every view) by Beier-Neely morphing with the 4, 8,
// 12 strongest bones or all of them, and compares it with the truly rendered cell: NCC (seed 000
// Table 2), PSNR and SSIM, beside the baselines of showing the previous key-frame and of a plain
// cross-dissolve of the neighbours. Also the texture memory with all and half the key-frames, and
// the time to morph one cell on the CPU and on the GPU. Writes impostor-quality.md, .csv and a plot
// (impostor-quality.png, through VTK: run under xvfb-run -a without a display).
//
// Also measures view blending: eye directions between baked views shown as the nearest view, the
// barycentric blend of three, or the smoothstep-biased blend, against the cell rendered from there.
//
//   throng-impostor-quality [--out DIR] [--size 128] [--keyframes 16] [--views 16x4]
//                           [--a A --b B --p P] [--asset NAME=SOURCE:CLIP ...]
// Exit codes: 0 done, 1 a measurement failed (the message says why), 2 a bad command line.

#include <algorithm>
#include <chrono>
#include <cctype>
#include <cstdlib>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "throng/actors/ActorTemplate.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/GpuMorpher.h"
#include "throng/render/ImageCompare.h"
#include "throng/render/ImageIO.h"
#include "throng/render/ImageSimilarity.h"
#include "throng/render/ImpostorBaker.h"
#include "throng/render/LimbMorph.h"
#include "throng/render/MorphCache.h"
#include "throng/render/MorphFeatures.h"
#include "throng/render/ProxyWarp.h"
#include "throng/support/CharacterSource.h"
#include "throng/support/CommandLine.h"
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

struct Row {
    std::string asset, clip, method;
    int features = 0;  // -1: not a morph
    double nccMean = 0, nccStd = 0, nccWhole = 0, psnr = 0, ssim = 0, cpuMs = 0, gpuMs = 0;
    int cells = 0;
};

// One row of the view-blending table: a way of showing an in-between eye direction.
struct ViewRow {
    std::string asset, method;
    double ncc = 0, nccWhole = 0, psnr = 0, ssim = 0;
};

struct Memory {
    std::string asset;
    std::size_t full = 0, half = 0;
};

double ms(std::chrono::steady_clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); }

// Accumulates the three metrics of approximations against truths.
struct Scores {
    std::vector<double> ncc, nccWhole, psnr, ssim;
    void add(const Image& approx, const Image& truth) {
        ncc.push_back(normalizedCrossCorrelation(approx, truth));
        nccWhole.push_back(normalizedCrossCorrelation(approx, truth, false));
        psnr.push_back(std::min(compareImages(approx, truth).psnr, 99.0));
        ssim.push_back(structuralSimilarity(approx, truth));
    }
    void into(Row& r) const {
        const auto mean = [](const std::vector<double>& v) {
            double s = 0;
            for (double x : v) s += x;
            return v.empty() ? 0.0 : s / static_cast<double>(v.size());
        };
        r.nccMean = mean(ncc);
        double var = 0;
        for (double x : ncc) var += (x - r.nccMean) * (x - r.nccMean);
        r.nccStd = ncc.size() > 1 ? std::sqrt(var / static_cast<double>(ncc.size() - 1)) : 0.0;
        r.psnr = mean(psnr);
        r.nccWhole = mean(nccWhole);
        r.ssim = mean(ssim);
        r.cells = static_cast<int>(ncc.size());
    }
};

// Premultiplied sum of the cells of `blend`'s views at stored key-frame `keyframe`.
Image blendViews(const ImpostorAtlas& atlas, const ViewBlend& blend, int keyframe) {
    Image out = atlas.cell(blend.views[0], keyframe);
    std::vector<float> acc(out.rgba.size(), 0.0f);
    for (std::size_t i = 0; i < 3; ++i) {
        if (blend.weights[i] <= 0.0f) continue;
        const Image c = atlas.cell(blend.views[i], keyframe);
        for (std::size_t j = 0; j < acc.size(); ++j) acc[j] += blend.weights[i] * static_cast<float>(c.rgba[j]);
    }
    for (std::size_t j = 0; j < acc.size(); ++j)
        out.rgba[j] = static_cast<std::uint8_t>(std::clamp(std::lround(acc[j]), 0L, 255L));
    return out;
}

// Eye directions between the baked views: the nearest view, the barycentric blend of three and the
// smoothstep-biased blend, against the cell rendered from that very direction.
void measureViews(const Asset& asset, ImpostorBaker& baker, const ImpostorAtlas& full, std::vector<ViewRow>& rows) {
    const ViewHemisphere& h = full.views();
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> az(0.0f, 6.2831853f), el(0.0f, h.elevation(h.elevations() - 1));
    Scores nearest, blend, smooth;
    for (int i = 0; i < 96; ++i) {
        const float a = az(rng), e = el(rng);
        const glm::vec3 dir(std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a));
        const int k = 2 * (i % (full.keyframeCount() / 2));
        const Image truth = baker.renderCell(full.duration() * k / full.keyframeCount(), dir);
        nearest.add(full.cell(h.nearest(dir), k), truth);
        blend.add(blendViews(full, h.blend(dir, false), k), truth);
        smooth.add(blendViews(full, h.blend(dir, true), k), truth);
    }
    for (auto [name, s] : {std::pair<const char*, Scores*>{"nearest view", &nearest}, {"barycentric blend of 3 views", &blend},
                           {"smoothstep-biased blend", &smooth}}) {
        Row r;
        s->into(r);
        rows.push_back({asset.name, name, r.nccMean, r.nccWhole, r.psnr, r.ssim});
    }
}

// One way of regenerating a dropped cell from automatic features.
struct FeatureVariant {
    std::string name;
    FeatureOptions features;
    MorphParameters parameters;
    bool limbs = false;  // occlusion-aware blend (morphLimbs) instead of the cross-dissolve
    VisibilityOptions visibility{};
    int oracle = 0;      // diagnostics: 1 per-pixel best of the two warps (needs the truth), 2 previous only, 3 next only
    long proxy = -1;     // warp through the figure's surface with at most this many vertices (0: all); -1: lines
    ProxyWarpOptions proxyOptions{};
};

// Proxy meshes of one asset by vertex budget, built on first use.
struct Proxies {
    ImpostorBaker* baker = nullptr;
    std::map<long, ProxyMesh> meshes;
    const ProxyMesh& get(long budget) {
        auto it = meshes.find(budget);
        if (it == meshes.end()) it = meshes.emplace(budget, baker->proxyMesh(static_cast<std::size_t>(budget))).first;
        return it->second;
    }
};

// Regenerates dropped key-frame `k` of `half` in view `v` as `variant` says: the occlusion-aware
// morph on the CPU, else the GPU morph when the features fit its uniforms, else the CPU morph.
Image morphVariant(const ImpostorAtlas& half, const FeatureTrack& track, std::uint32_t v, int k, const FeatureVariant& variant,
                   GpuMorpher* gpu, unsigned threads, const Image* truth = nullptr, Proxies* proxies = nullptr) {
    int before = 0, after = 0;
    float t = 0.5f;
    half.neighbours(k, before, after, t);
    if (variant.proxy >= 0) {
        const Image a = half.cell(v, before), b = half.cell(v, after);
        const glm::vec3 eye = half.views().direction(v);
        const ProxySource sources[2] = {{&a, eye, before, 1.0f - t}, {&b, eye, after, t}};
        if (variant.oracle) {
            const ProxySource s0[1] = {sources[0]}, s1[1] = {sources[1]};
            const Image w0 = warpProxy(proxies->get(variant.proxy), s0, eye, k, variant.proxyOptions);
            const Image w1 = warpProxy(proxies->get(variant.proxy), s1, eye, k, variant.proxyOptions);
            if (variant.oracle == 2) return w0;
            if (variant.oracle == 3) return w1;
            Image best = w0;
            for (std::size_t i = 0; i < best.rgba.size(); i += 4) {
                int e0 = 0, e1 = 0;
                for (int c = 0; c < 4; ++c) e0 += std::abs(w0.rgba[i + c] - truth->rgba[i + c]), e1 += std::abs(w1.rgba[i + c] - truth->rgba[i + c]);
                if (e1 < e0) std::copy_n(&w1.rgba[i], 4, &best.rgba[i]);
            }
            return best;
        }
        return warpProxy(proxies->get(variant.proxy), sources, eye, k, variant.proxyOptions);
    }
    const CellFeatures f = droppedCellFeatures(half, track, v, k, variant.features);
    const Image a = half.cell(v, before), b = half.cell(v, after);
    if (variant.oracle) {
        const Image w0 = morphImages(a, f.from, b, f.to, f.target, 0.0f, variant.parameters, threads, f.targetAttributes);
        const Image w1 = morphImages(a, f.from, b, f.to, f.target, 1.0f, variant.parameters, threads, f.targetAttributes);
        if (variant.oracle == 2) return w0;
        if (variant.oracle == 3) return w1;
        Image best = w0;
        for (std::size_t i = 0; i < best.rgba.size(); i += 4) {
            int e0 = 0, e1 = 0;
            for (int c = 0; c < 4; ++c) e0 += std::abs(w0.rgba[i + c] - truth->rgba[i + c]), e1 += std::abs(w1.rgba[i + c] - truth->rgba[i + c]);
            if (e1 < e0) std::copy_n(&w1.rgba[i], 4, &best.rgba[i]);
        }
        return best;
    }
    if (variant.limbs) return morphLimbs(a, b, f, track, t, variant.parameters, variant.visibility, threads);
    if (gpu && f.target.size() <= GpuMorpher::kMaxLines) return gpu->morph(a, f.from, b, f.to, f.target, t, variant.parameters, f.targetAttributes);
    return morphImages(a, f.from, b, f.to, f.target, t, variant.parameters, threads, f.targetAttributes);
}

// Side by side, 4x, over grey: for looking at a few cells while experimenting.
Image contactSheet(const std::vector<Image>& cells) {
    const int z = 4, w = cells.front().width, h = cells.front().height;
    Image out;
    out.width = w * z * static_cast<int>(cells.size());
    out.height = h * z;
    out.rgba.assign(static_cast<std::size_t>(out.width) * out.height * 4, 255);
    for (std::size_t c = 0; c < cells.size(); ++c)
        for (int y = 0; y < out.height; ++y)
            for (int x = 0; x < w * z; ++x) {
                const std::uint8_t* p = &cells[c].rgba[(static_cast<std::size_t>(y / z) * w + x / z) * 4];
                std::uint8_t* o = &out.rgba[(static_cast<std::size_t>(y) * out.width + c * w * z + x) * 4];
                for (int k = 0; k < 3; ++k) o[k] = static_cast<std::uint8_t>(p[k] + (255 - p[3]) * 96 / 255);
            }
    return out;
}

// Every dropped cell regenerated by each variant, against the truly rendered cell.
void measureVariants(const Asset& asset, const ImpostorAtlas& full, const ImpostorAtlas& half, const FeatureTrack& track,
                     const std::vector<FeatureVariant>& variants, GpuMorpher* gpu, Proxies& proxies, std::vector<Row>& rows) {
    for (const FeatureVariant& variant : variants) {
        Scores s;
        const auto t0 = std::chrono::steady_clock::now();
        std::size_t lines = 0;
        for (int k = 1; k < half.keyframeCount(); k += 2)
            for (std::uint32_t v = 0; v < half.views().viewCount(); ++v) {
                const Image truth = full.cell(v, k);
                const Image m = morphVariant(half, track, v, k, variant, gpu, 2, &truth, &proxies);
                s.add(m, truth);
                if (std::getenv("IMPQ_SHEET") && k == std::atoi(std::getenv("IMPQ_SHEET")) && v % 4 == 0 && v < 32) {
                    std::string name = variant.name;
                    for (char& c : name) if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                    Image diff = truth;
                    for (std::size_t i = 0; i < diff.rgba.size(); i += 4) {
                        int e = 0;
                        for (int c = 0; c < 4; ++c) e = std::max(e, std::abs(m.rgba[i + c] - truth.rgba[i + c]));
                        diff.rgba[i] = diff.rgba[i + 1] = diff.rgba[i + 2] = static_cast<std::uint8_t>(std::min(255, e * 4));
                        diff.rgba[i + 3] = 255;
                    }
                    writePng(contactSheet({half.cell(v, k - 1), m, truth, half.cell(v, k + 1 < half.keyframeCount() ? k + 1 : 0), diff}),
                             "/tmp/impq/sheet-" + name + "-v" + std::to_string(v) + ".png");
                }
                if (lines == 0)
                    lines = variant.proxy >= 0 ? proxies.get(variant.proxy).vertexCount()
                                               : droppedCellFeatures(half, track, v, k, variant.features).target.size();
            }
        Row row{asset.name, full.clipName(), variant.name, static_cast<int>(lines)};
        s.into(row);
        if (std::getenv("IMPQ_RINGS")) {
            const std::uint32_t az = static_cast<std::uint32_t>(half.views().azimuths());
            std::vector<double> ring(static_cast<std::size_t>(half.views().elevations()), 0.0), kf(static_cast<std::size_t>(half.keyframeCount()), 0.0);
            std::size_t i = 0;
            for (int k = 1; k < half.keyframeCount(); k += 2)
                for (std::uint32_t v = 0; v < half.views().viewCount(); ++v, ++i) ring[v / az] += s.ncc[i], kf[static_cast<std::size_t>(k)] += s.ncc[i];
            std::fprintf(stderr, "   rings:");
            for (double r : ring) std::fprintf(stderr, " %.4f", r / (static_cast<double>(s.ncc.size()) / static_cast<double>(ring.size())));
            std::fprintf(stderr, "  key-frames:");
            for (int k = 1; k < half.keyframeCount(); k += 2) std::fprintf(stderr, " %.4f", kf[static_cast<std::size_t>(k)] / half.views().viewCount());
            std::fprintf(stderr, "\n");
        }
        row.gpuMs = ms(std::chrono::steady_clock::now() - t0) / row.cells;
        rows.push_back(row);
        std::fprintf(stderr, "%s: %s (%zu features): NCC %.4f PSNR %.2f SSIM %.4f, %.1f ms/cell\n", asset.name.c_str(), variant.name.c_str(),
                     lines, row.nccMean, row.psnr, row.ssim, row.gpuMs);
    }
}

std::vector<FeatureVariant> featureVariants(const MorphParameters& base) {
    std::vector<FeatureVariant> v;
    const auto add = [&](std::string name, auto edit) {
        FeatureVariant f{std::move(name), {}, base};
        edit(f);
        v.push_back(f);
    };
    add("bones (track)", [](FeatureVariant&) {});
    const char* only = std::getenv("IMPQ_ONLY");
    if (!only || std::string(only) == "diag") {
        add("diag: previous warped only", [](FeatureVariant& f) { f.oracle = 2; });
        add("diag: next warped only", [](FeatureVariant& f) { f.oracle = 3; });
        add("diag: per-pixel best of the two warps", [](FeatureVariant& f) { f.oracle = 1; });
        add("diag: capsules, per-pixel best", [](FeatureVariant& f) { f.features.capsules = true, f.oracle = 1; });
    }
    if (only && std::string(only) == "proxydiag") {
        add("proxy: previous only", [](FeatureVariant& f) { f.proxy = 0, f.oracle = 2; });
        add("proxy: next only", [](FeatureVariant& f) { f.proxy = 0, f.oracle = 3; });
        add("proxy: per-pixel best", [](FeatureVariant& f) { f.proxy = 0, f.oracle = 1; });
        add("proxy", [](FeatureVariant& f) { f.proxy = 0; });
        add("proxy opaque", [](FeatureVariant& f) { f.proxy = 0, f.proxyOptions.opaqueInside = true; });
        add("proxy opaque, no visibility", [](FeatureVariant& f) { f.proxy = 0, f.proxyOptions.opaqueInside = true, f.proxyOptions.distrust = 1; });
        add("proxy opaque tol 4", [](FeatureVariant& f) { f.proxy = 0, f.proxyOptions.opaqueInside = true, f.proxyOptions.depthTolerance = 4; });
        add("proxy opaque bicubic", [](FeatureVariant& f) { f.proxy = 0, f.proxyOptions.opaqueInside = true, f.proxyOptions.bicubic = true; });
        add("proxy opaque normals 16", [](FeatureVariant& f) { f.proxy = 0, f.proxyOptions.opaqueInside = true, f.proxyOptions.normalSharpness = 16; });
        for (long budget : {2000L, 1000L, 500L})
            add("proxy " + std::to_string(budget) + " opaque", [budget](FeatureVariant& f) { f.proxy = budget, f.proxyOptions.opaqueInside = true; });
        add("proxy 1000 opaque rim 1", [](FeatureVariant& f) { f.proxy = 1000, f.proxyOptions.opaqueInside = true, f.proxyOptions.rim = 1; });
    }
    if (!only || std::string(only) == "proxy") {
        for (long budget : {0L, 2000L, 800L, 300L}) {
            add("proxy " + std::to_string(budget), [budget](FeatureVariant& f) { f.proxy = budget; });
            add("proxy " + std::to_string(budget) + ", no visibility", [budget](FeatureVariant& f) { f.proxy = budget, f.proxyOptions.distrust = 1.0f; });
        }
    }
    if (!only || std::string(only) == "caps") {
        for (float r : {0.5f, 0.75f, 1.0f, 1.25f, 1.5f})
            add("capsules x" + std::to_string(r).substr(0, 4), [r](FeatureVariant& f) { f.features.capsules = true, f.features.radiusScale = r; });
    }
    if (!only || std::string(only) == "depth") {
        for (float d : {0.1f, 0.3f, 1.0f, 3.0f})
            add("capsules + depth " + std::to_string(d).substr(0, 4), [d](FeatureVariant& f) { f.features.capsules = true, f.parameters.depth = d; });
        add("capsules + depth 0.3 + visibility", [](FeatureVariant& f) { f.features.capsules = true, f.parameters.depth = 0.3f, f.limbs = true; });
    }
    return v;
}

void measure(const Asset& asset, const ImpostorBakeOptions& options, const MorphParameters& parameters, const std::filesystem::path& out,
             std::vector<Row>& rows, std::vector<Memory>& memory, std::vector<ViewRow>& viewRows) {
    const auto tmpl = support::loadTemplate(asset.source);
    const int clip = support::findClipOrThrow(*tmpl, asset.clip);
    auto context = createContext(ContextOptions{options.cellSize, options.cellSize, false});
    ImpostorBaker baker(context, tmpl, clip, options);
    std::fprintf(stderr, "%s: baking...\n", asset.name.c_str());
    const ImpostorAtlas full = baker.bake();
    ImpostorAtlas half = full;
    half.dropOddKeyframes();
    memory.push_back({asset.name, full.textureBytes(), half.textureBytes()});
    const std::string clipName = full.clipName();
    GpuMorpher gpu(context);
    const FeatureTrack track = baker.featureTrack();
    {
        std::fprintf(stderr, "%s: radii (px):", asset.name.c_str());
        for (std::size_t i = 0; i < track.boneCount(); ++i) std::fprintf(stderr, " %s=%.1f/%u", full.boneNames()[i].c_str(), track.radii()[i] * track.pixelsPerMetre(), track.limbs()[i]);
        std::fprintf(stderr, "\n");
    }
    if (std::getenv("IMPQ_FEATURES")) {
        Proxies proxies{&baker, {}};
        measureVariants(asset, full, half, track, featureVariants(parameters), &gpu, proxies, rows);
        return;
    }
    measureViews(asset, baker, full, viewRows);

    // Baselines.
    Scores previous, dissolve;
    for (int k = 1; k < half.keyframeCount(); k += 2)
        for (std::uint32_t v = 0; v < half.views().viewCount(); ++v) {
            const Image truth = full.cell(v, k);
            previous.add(half.cell(v, k - 1), truth);
            MorphCacheOptions none;
            none.features = 0;
            none.parameters = parameters;
            dissolve.add(morphDroppedCell(half, v, k, none, &gpu), truth);
        }
    Row r{asset.name, clipName, "previous key-frame", -1};
    previous.into(r);
    rows.push_back(r);
    r = Row{asset.name, clipName, "cross-dissolve", 0};
    dissolve.into(r);
    rows.push_back(r);

    const std::size_t all = half.boneCount();
    struct Variant {
        std::size_t features;
        bool skeletonTargets;
    };
    std::vector<Variant> variants;
    for (std::size_t f : {std::size_t{4}, std::size_t{8}, std::size_t{12}, all})
        if (f <= all && (variants.empty() || variants.back().features != f)) variants.push_back({f, true});
    variants.push_back({all, false});
    for (const Variant& variant : variants) {
        MorphCacheOptions o;
        o.parameters = parameters;
        o.features = variant.features;
        o.skeletonTargets = variant.skeletonTargets;
        Scores s;
        double gpuMs = 0;
        for (int k = 1; k < half.keyframeCount(); k += 2)
            for (std::uint32_t v = 0; v < half.views().viewCount(); ++v) {
                const auto t0 = std::chrono::steady_clock::now();
                const Image m = morphDroppedCell(half, v, k, o, &gpu);
                gpuMs += ms(std::chrono::steady_clock::now() - t0);
                s.add(m, full.cell(v, k));
                if (variant.features == all && variant.skeletonTargets && k == 1 && v == 4) {
                    writePng(m, out / (asset.name + "-morphed.png"));
                    writePng(full.cell(v, k), out / (asset.name + "-truth.png"));
                    writePng(half.cell(v, k - 1), out / (asset.name + "-previous.png"));
                }
            }
        // CPU time on a sample of cells (it is the reference, not the run-time path).
        double cpuMs = 0;
        int cpuCells = 0;
        for (std::uint32_t v = 0; v < half.views().viewCount(); v += 8, ++cpuCells) {
            const auto t0 = std::chrono::steady_clock::now();
            (void)morphDroppedCell(half, v, 1, o);
            cpuMs += ms(std::chrono::steady_clock::now() - t0);
        }
        Row row{asset.name, clipName,
                variant.skeletonTargets ? "morph (skeleton targets)" : "morph (interpolated lines)",
                static_cast<int>(variant.features)};
        s.into(row);
        row.gpuMs = gpuMs / row.cells;
        row.cpuMs = cpuMs / cpuCells;
        rows.push_back(row);
        std::fprintf(stderr, "%s: %s, %zu features: NCC %.4f\n", asset.name.c_str(), row.method.c_str(), variant.features,
                     row.nccMean);
    }
}

}  // namespace

int main(int argc, char** argv) {
    std::filesystem::path out = "impostor-report";
    ImpostorBakeOptions options;
    MorphParameters parameters;
    std::vector<Asset> assets;
    const std::string shared = THRONG_SHARED_ASSETS;
    std::string outText = out.string();
    support::ViewGrid views{options.azimuths, options.elevations};
    std::vector<std::string> assetTexts;
    support::CommandLine cl("throng-impostor-quality",
                            "How good morphed impostor key-frames are and what they cost: NCC, PSNR and SSIM of morphed\n"
                            "against truly rendered cells, texture memory, morph time, view blending. Writes\n"
                            "impostor-quality.md, .csv and .png (the plot through VTK: without a display, run under\n"
                            "xvfb-run -a).");
    CLI::App& app = cl.app();
    app.add_option("--out", outText, "folder for the report")->type_name("DIR");
    app.add_option("--size", options.cellSize, "cell side")->type_name("PIXELS")->check(support::wholeNumber(8, 4096));
    app.add_option("--keyframes", options.keyframes, "key-frames over the clip (odd ones are dropped and morphed)")
        ->type_name("N")
        ->check(support::wholeNumber(2, 1024));
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
        ->default_str("CesiumMan, robot and seed-humanoid");
    if (const auto code = cl.parse(argc, argv)) return *code;
    out = outText;
    options.azimuths = views.azimuths;
    options.elevations = views.elevations;
    for (const std::string& text : assetTexts) assets.push_back(*parseAsset(text));
    try {
        if (assets.empty())
            assets = {{"CesiumMan", shared + "/characters/CesiumMan.glb", ""},
                      {"robot", shared + "/characters/robot.glb", "Robot_Walking"},
                      {"seed-humanoid", "seed-humanoid", "walk"}};
        std::filesystem::create_directories(out);
        std::vector<Row> rows;
        std::vector<Memory> memory;
        std::vector<ViewRow> viewRows;
        for (const Asset& a : assets) measure(a, options, parameters, out, rows, memory, viewRows);

        std::ofstream csv(out / "impostor-quality.csv");
        csv << "asset,clip,method,features,ncc_mean,ncc_std,ncc_whole_cell,psnr_db,ssim,cells,gpu_ms_per_cell,cpu_ms_per_cell\n";
        for (const Row& r : rows)
            csv << r.asset << ',' << r.clip << ',' << r.method << ',' << r.features << ',' << r.nccMean << ',' << r.nccStd << ',' << r.nccWhole
                << ',' << r.psnr << ',' << r.ssim << ',' << r.cells << ',' << r.gpuMs << ',' << r.cpuMs << '\n';
        std::ostringstream md;
        char line[512];
        md << "# Impostor morphing: quality and cost\n\n";
        md << "Cells of " << options.cellSize << " px, " << options.azimuths << " x " << options.elevations
           << " views, " << options.keyframes << " key-frames, Beier-Neely a = " << parameters.a << " px, b = " << parameters.b << ", p = " << parameters.p
           << ", odd key-frames dropped and regenerated; every view of "
           << "every dropped key-frame compared with the truly rendered cell (NCC and SSIM over the pixels either image "
           << "covers). Time per cell: GPU = the fragment-shader morph (llvmpipe here), CPU = the reference, one "
           << "thread.\n\n";
        md << "| asset | clip | method | features | NCC mean | NCC std | NCC whole cell | PSNR dB | SSIM | GPU ms/cell | CPU ms/cell |\n";
        md << "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for (const Row& r : rows) {
            std::snprintf(line, sizeof line, "| %s | %s | %s | %s | %.4f | %.4f | %.4f | %.2f | %.4f | %s | %s |\n",
                          r.asset.c_str(), r.clip.c_str(), r.method.c_str(),
                          r.features < 0 ? "-" : std::to_string(r.features).c_str(), r.nccMean, r.nccStd, r.nccWhole, r.psnr, r.ssim,
                          r.features <= 0 ? "-" : (std::to_string(r.gpuMs).substr(0, 5)).c_str(),
                          r.features <= 0 ? "-" : (std::to_string(r.cpuMs).substr(0, 5)).c_str());
            md << line;
        }
        md << "\n| asset | texture, all key-frames | texture, half | ratio |\n|---|---:|---:|---:|\n";
        for (const Memory& m : memory) {
            std::snprintf(line, sizeof line, "| %s | %.2f MiB | %.2f MiB | %.1f%% |\n", m.asset.c_str(),
                          static_cast<double>(m.full) / 1048576.0, static_cast<double>(m.half) / 1048576.0,
                          100.0 * static_cast<double>(m.half) / static_cast<double>(m.full));
            md << line;
        }
        md << "\nView blending: 96 random eye directions between the baked views (stored key-frames), against "
              "the cell rendered from that direction:\n\n| asset | shown | NCC | NCC whole cell | PSNR dB | SSIM |\n"
              "|---|---|---:|---:|---:|---:|\n";
        for (const ViewRow& v : viewRows) {
            std::snprintf(line, sizeof line, "| %s | %s | %.4f | %.4f | %.2f | %.4f |\n", v.asset.c_str(), v.method.c_str(),
                          v.ncc, v.nccWhole, v.psnr, v.ssim);
            md << line;
        }
        std::ofstream(out / "impostor-quality.md") << md.str();
        std::printf("%s", md.str().c_str());

        // The plot: NCC against feature count per asset, baselines dashed.
        vtk::Chart chart;
        chart.title = "Morphed impostor key-frames against truly rendered ones";
        chart.xLabel = "feature lines (bones)";
        chart.yLabel = "mean NCC";
        chart.legend = vtk::Chart::Legend::Bottom;
        int colour = 0;
        for (const Asset& a : assets) {
            vtk::ChartSeries morph, prev;
            morph.name = a.name + ": morph";
            prev.name = a.name + ": previous key-frame";
            morph.style = vtk::ChartSeries::Style::LineAndPoints;
            prev.style = vtk::ChartSeries::Style::DashedLine;
            vtk::paletteColour(colour, morph.rgb);
            vtk::paletteColour(colour++, prev.rgb);
            double baseline = 0;
            for (const Row& r : rows) {
                if (r.asset != a.name) continue;
                if (r.features < 0) baseline = r.nccMean;
                else if (r.method != "morph (interpolated lines)") morph.x.push_back(r.features), morph.y.push_back(r.nccMean);
            }
            prev.x = {morph.x.front(), morph.x.back()};
            prev.y = {baseline, baseline};
            chart.series.push_back(morph);
            chart.series.push_back(prev);
        }
        try {
            vtk::writeChartPng(chart, (out / "impostor-quality.png").string());
        } catch (const std::exception& e) {
            std::fprintf(stderr, "no plot (%s); run under xvfb-run -a\n", e.what());
        }
        std::fprintf(stderr, "written to %s\n", out.c_str());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "throng-impostor-quality: %s\n", e.what());
        return 1;
    }
}
