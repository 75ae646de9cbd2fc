#include "StaticTemplateBuilder.h"

#include <algorithm>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include "throng/actors/ActorTemplate.h"
#include "throng/scenegraph/MeshDrawable.h"

namespace throng::gltf {

std::optional<LoadedCharacter> buildStaticTemplate(GltfDocument& doc, const GltfContent& content, const std::set<int>& claimed,
                                                   const GltfLoadOptions& options, const std::string& name) {
    std::vector<int> statics;
    for (std::size_t i = 0; i < content.primitives.size(); ++i)
        if (content.primitives[i].skin < 0 && !claimed.count(static_cast<int>(i))) statics.push_back(static_cast<int>(i));
    if (statics.empty()) return std::nullopt;
    ActorTemplateBuilder builder(doc.model.skins.empty() ? name : name + "/static");
    LoadedCharacter ch;
    std::vector<dvec3> extent;
    std::set<std::string> names;
    for (int i : statics) {
        const ReadPrimitive& p = content.primitives[static_cast<std::size_t>(i)];
        SkeletonNode g;
        g.name = p.world->name;
        for (int k = 2; names.count(g.name); ++k) g.name = p.world->name + "#" + std::to_string(k);
        names.insert(g.name);
        g.geometry.addLevel(std::numeric_limits<double>::infinity(), std::make_shared<MeshDrawable>(p.world));
        for (const auto& v : p.world->positions) extent.push_back(dvec3(v));
        builder.addNode(g);
        ch.nodeSource.push_back(p.node);
        ch.primitives.push_back(i);
    }
    const double margin = options.sklsrootMargin >= 0 ? options.sklsrootMargin : std::max(0.05, 0.01 * restExtent(extent));
    try {
        builder.setSkeletonRootMargin(margin);
        builder.setRadiusSampleRate(options.sklsrootSampleRate);
        ch.tmpl = builder.build();
    } catch (const std::invalid_argument& e) {
        doc.fail("/meshes", e.what());
    }
    return ch;
}

}  // namespace throng::gltf
