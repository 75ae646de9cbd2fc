#pragma once
// One process's copy of a crowd of skinned bars with a key-pose cache, as the tests of processes
// (and ranks) that each pose a share of one crowd build it in every process (header only).

#include <memory>

#include "throng/actors/ActorDrawReferences.h"
#include "throng/actors/ActorProcessor.h"
#include "throng/actors/KeyPoseCache.h"
#include "throng/testkit/ActorTestScenes.h"

namespace throng::testkit {

/// The bars, the share of them this process holds (`behaviour->here`), its processor and numbering.
struct CachedBars {
    Crowd crowd;                                                         ///< the bars
    std::shared_ptr<KeyframeShare> behaviour = std::make_shared<KeyframeShare>();  ///< which are held here
    std::shared_ptr<Group> root = std::make_shared<Group>();            ///< the scene: one group of them
    std::unique_ptr<ActorProcessor> processor;                          ///< actor processing of the scene
    DrawReferences refs;                                                ///< what their items point to, numbered
};

/// `count` bars on a grid (barGrid), a processor with a key-pose cache of `rows` rows in `mode`
/// for the band beyond 10 m (hysteresis 1 m), and the draw numbering of the result.
inline std::unique_ptr<CachedBars> cachedBars(int count, std::uint32_t rows, KeyPoseMode mode = KeyPoseMode::Intermittent) {
    static const auto tmpl = skinnedBar();
    auto b = std::make_unique<CachedBars>();
    b->root->addChild(barGrid(b->crowd, b->behaviour, tmpl, count));
    b->processor = std::make_unique<ActorProcessor>(b->crowd);
    KeyPoseCacheSettings settings;
    settings.rows = rows;
    settings.mode = mode;
    b->processor->setKeyPoseCache(std::make_shared<KeyPoseCache>(tmpl, settings));
    b->processor->setKeyPoseDistance(10.0, 1.0);
    b->refs = actorDrawReferences(b->crowd, *b->root, *b->processor);
    return b;
}

}  // namespace throng::testkit
