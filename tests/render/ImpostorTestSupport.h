#pragma once
// Shared by the impostor tests: a small impostor of the procedural seed humanoid's walk, baked
// once per test program (few views, small cells, so llvmpipe bakes it in a second or two).

#include <memory>

#include "throng/actors/SeedHumanoid.h"
#include "throng/render/ContextFactory.h"
#include "throng/render/ImpostorAtlas.h"
#include "throng/render/ImpostorBaker.h"

namespace throng::test {

/// A headless context, the humanoid, its baker and its full atlas (all key-frames stored).
struct BakedHumanoid {
    std::shared_ptr<GlContext> context;
    std::shared_ptr<const ActorTemplate> tmpl;
    std::unique_ptr<ImpostorBaker> baker;
    std::unique_ptr<ImpostorAtlas> full;

    /// Bakes `elevations` view rings (8 views around, 8 key-frames, 64 px cells).
    explicit BakedHumanoid(int elevations = 2) {
        context = createContext(ContextOptions{64, 64, false});
        tmpl = makeSeedHumanoid();
        ImpostorBakeOptions options;
        options.azimuths = 8;
        options.elevations = elevations;
        options.keyframes = 8;
        options.cellSize = 64;
        baker = std::make_unique<ImpostorBaker>(context, tmpl, tmpl->findClip("walk"), options);
        full = std::make_unique<ImpostorAtlas>(baker->bake());
    }

    /// The process-wide instance (baked on first use).
    static BakedHumanoid& get() {
        static BakedHumanoid baked;
        return baked;
    }
    /// A process-wide instance with four view rings, for dropping every other one.
    static BakedHumanoid& fourRings() {
        static BakedHumanoid baked(4);
        return baked;
    }
};

}  // namespace throng::test
