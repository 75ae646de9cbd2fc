// throng-bake: bakes impostors (DESIGN.md, Impostors). For a character and clip, renders
// orthographic views on a hemisphere x key-frames with alpha into atlas PNGs (one per stored
// key-frame) and impostor.json (views, key-frames, projected bone segments per cell), drops every
// other key-frame (regenerated at run time by morphing) unless --keep-all, and prints the texture
// memory of the template.
//
//   throng-bake FILE.glb --out DIR [--clip NAME] [--views 16x4] [--keyframes 16] [--size 128]
//               [--features FILE.json] [--keep-all]
//   throng-bake seed-humanoid --out DIR          (the procedural figure, no asset needed)

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "../town/ProgressBar.h"
#include "CharacterSource.h"
#include "throng/actors/ActorTemplate.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/ImpostorBaker.h"

namespace {

void usage(std::FILE* out) {
    std::fprintf(out,
                 "usage: throng-bake FILE.glb|seed-humanoid --out DIR [--clip NAME] [--views AxE] [--keyframes N]\n"
                 "                   [--size PIXELS] [--features FILE.json] [--keep-all]\n"
                 "  --views AxE      azimuths x elevations on the hemisphere (default 16x4)\n"
                 "  --keyframes N    key-frames over the clip (default 16; odd ones are dropped)\n"
                 "  --size PIXELS    cell side (default 128)\n"
                 "  --features FILE  hand-written feature lines overriding the skeleton's bones\n"
                 "  --keep-all       keep every key-frame (no morphing needed)\n");
}

int toInt(const std::string& s, const char* what) {
    try {
        std::size_t used = 0;
        const int v = std::stoi(s, &used);
        if (used == s.size()) return v;
    } catch (const std::exception&) {
    }
    throw std::runtime_error(std::string("bad value for ") + what + ": '" + s + "'");
}

std::string mib(std::size_t bytes) {
    char text[64];
    std::snprintf(text, sizeof text, "%.2f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
    return text;
}

}  // namespace

int main(int argc, char** argv) {
    using namespace throng;
    std::string input, out, clipName, features;
    ImpostorBakeOptions options;
    bool keepAll = false;
    try {
        for (int i = 1; i < argc; ++i) {
            const std::string a = argv[i];
            const auto next = [&]() -> std::string {
                if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
                return argv[++i];
            };
            if (a == "--help" || a == "-h") {
                usage(stdout);
                return 0;
            } else if (a == "--out") out = next();
            else if (a == "--clip") clipName = next();
            else if (a == "--keyframes") options.keyframes = toInt(next(), "--keyframes");
            else if (a == "--size") options.cellSize = toInt(next(), "--size");
            else if (a == "--features") features = next();
            else if (a == "--keep-all") keepAll = true;
            else if (a == "--views") {
                const std::string v = next();
                const auto x = v.find('x');
                if (x == std::string::npos) throw std::runtime_error("--views wants AxE, e.g. 16x4");
                options.azimuths = toInt(v.substr(0, x), "--views");
                options.elevations = toInt(v.substr(x + 1), "--views");
            } else if (!a.empty() && a[0] == '-') throw std::runtime_error("unknown option " + a);
            else if (input.empty()) input = a;
            else throw std::runtime_error("more than one input: '" + input + "' and '" + a + "'");
        }
        if (input.empty() || out.empty()) {
            usage(stderr);
            return 2;
        }
        const auto tmpl = bake::loadTemplate(input);
        const int clip = bake::findClipOrThrow(*tmpl, clipName);
        town::ProgressBar bar("baking " + tmpl->name() + "/" + tmpl->clips()[static_cast<std::size_t>(clip)]->name(),
                              static_cast<std::size_t>(options.keyframes));
        options.progress = [&](int done, int total) {
            bar.update(static_cast<std::size_t>(done), std::to_string(done) + "/" + std::to_string(total) + " key-frames");
        };
        auto context = createContext(ContextOptions{options.cellSize, options.cellSize, false});
        ImpostorBaker baker(context, tmpl, clip, options);
        ImpostorAtlas atlas = baker.bake();
        bar.finish();
        if (!features.empty()) atlas.applyFeatureFile(features);
        const std::size_t full = atlas.fullTextureBytes();
        if (!keepAll) atlas.dropOddKeyframes();
        atlas.save(out);
        std::printf("%s / %s: %u views x %d key-frames (%d stored) of %d px, %zu feature lines per cell\n",
                    tmpl->name().c_str(), atlas.clipName().c_str(), atlas.views().viewCount(), atlas.keyframeCount(),
                    [&] { int n = 0; for (int k = 0; k < atlas.keyframeCount(); ++k) n += atlas.stored(k); return n; }(),
                    atlas.cellSize(), atlas.boneCount());
        std::printf("texture memory per template: %s (all key-frames: %s, %.1f%%)\n", mib(atlas.textureBytes()).c_str(),
                    mib(full).c_str(), 100.0 * static_cast<double>(atlas.textureBytes()) / static_cast<double>(full));
        std::printf("written to %s\n", out.c_str());
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "throng-bake: %s\n", e.what());
        return 1;
    }
}
