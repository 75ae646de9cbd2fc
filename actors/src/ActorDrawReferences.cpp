#include "throng/actors/ActorDrawReferences.h"

#include <unordered_set>

#include "throng/actors/ActorProcessor.h"
#include "throng/actors/ActorTemplate.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/KeyPoseCache.h"
#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/NodeVisitor.h"

namespace throng {
namespace {

// Numbers the crowd's nodes in the order the traversal meets them.
class ActorNodeNumbering : public NodeVisitor {
public:
    ActorNodeNumbering(const Crowd& crowd, DrawReferences& refs) : refs_(refs), actorNodes_(crowd.nodes().begin(), crowd.nodes().end()) {}
    void apply(Node& node) override {
        if (actorNodes_.count(&node)) refs_.addNode(node);
    }

private:
    DrawReferences& refs_;
    std::unordered_set<const Node*> actorNodes_;
};

void numberLevels(const VaLod& lod, DrawReferences& refs) {
    for (const VaLodLevel& level : lod.levels())
        if (level.drawable) refs.addDrawable(*level.drawable);
}

}  // namespace

DrawReferences actorDrawReferences(const Crowd& crowd, Node& root, const ActorProcessor& processor) {
    DrawReferences refs;
    ActorNodeNumbering nodes(crowd, refs);
    root.accept(nodes);
    const Crowd::State& s = crowd.state();
    std::unordered_set<const ActorTemplate*> seen;
    for (std::size_t id = 0; id < crowd.size(); ++id) {
        const ActorTemplate* t = s.tmpl[id];
        if (!t || !seen.insert(t).second) continue;
        numberLevels(t->rootGeometry(), refs);
        for (const SkeletonNode& node : t->nodes()) numberLevels(node.geometry, refs);
        if (const Drawable* impostor = processor.impostorOf(*t)) refs.addDrawable(*impostor);
        for (const auto& cache : processor.keyPoseCaches())
            if (&cache->actorTemplate() == t) refs.addKeyPoseSource(*cache);
    }
    for (const std::vector<HeldObject>& held : s.heldObjects)
        for (const HeldObject& object : held)
            if (object.drawable) refs.addDrawable(*object.drawable);
    return refs;
}

}  // namespace throng
