// throng-inspect FILE: what the glTF loader makes of a file (templates, joint tree, morph targets, clips,
// primitives, bounding spheres, warnings). Exit 1 with "file: where: problem" when it cannot load,
// 2 on a bad command line (no file, a file that does not exist, an unknown option).

#include <cstdio>
#include <iostream>
#include <string>

#include "throng/gltf/GltfLoader.h"
#include "throng/support/CommandLine.h"
#include "throng/support/Validators.h"

using namespace throng;

namespace {

void printCharacter(const CharacterAsset& asset, const LoadedCharacter& c) {
    const ActorTemplate& t = *c.tmpl;
    std::size_t triangles = 0, vertices = 0;
    for (int p : c.primitives) {
        triangles += asset.primitives[static_cast<std::size_t>(p)].data->triangleCount();
        vertices += asset.primitives[static_cast<std::size_t>(p)].data->vertexCount();
    }
    std::printf("template '%s'%s\n", t.name().c_str(), c.skin >= 0 ? "" : " (rigid)");
    if (c.skin >= 0) std::printf("  skin %d: %d joints\n", c.skin, c.jointCount);
    std::printf("  Skeleton nodes: %zu, DOFs: %u, primitives: %zu, triangles: %zu, vertices: %zu\n", t.nodeCount(),
                t.dofCount(), c.primitives.size(), triangles, vertices);
    std::printf("  Sklsroot sphere radius: %.4g (margin %.4g), reach bound: %.4g\n", t.skeletonRootRadius(),
                t.skeletonRootMargin(), t.reachRadius());
    std::printf("  joints:\n");
    std::vector<int> depth(t.nodeCount(), 0);
    for (std::size_t i = 0; i < t.nodeCount(); ++i) {
        const SkeletonNode& n = t.nodes()[i];
        depth[i] = n.parent >= 0 ? depth[static_cast<std::size_t>(n.parent)] + 1 : 0;
        std::printf("    %*s%s", depth[i] * 2, "", n.name.c_str());
        if (n.dofs.empty()) std::printf(" (no DOF)");
        if (n.geometrySphere.valid())
            std::printf("  sphere (%.3g, %.3g, %.3g) r %.3g", n.geometrySphere.center().x, n.geometrySphere.center().y,
                        n.geometrySphere.center().z, n.geometrySphere.radius());
        std::printf("\n");
    }
    std::printf("  morph channels: %zu\n", t.morphChannels().size());
    for (std::size_t k = 0; k < t.morphChannels().size(); ++k)
        std::printf("    %-24s rest weight %.3g\n", t.morphChannels()[k].c_str(), t.restDofs()[t.morphWeightOffset() + k]);
    std::printf("  clips: %zu\n", t.clips().size());
    for (const auto& clip : t.clips()) {
        std::size_t weights = 0;
        for (const ClipChannel& ch : clip->channels()) weights += ch.target == ClipChannel::Target::MorphWeight;
        std::printf("    %-24s %8.3f s  %zu channels", clip->name().c_str(), clip->duration(), clip->channels().size());
        if (weights) std::printf(" (%zu of morph weights)", weights);
        std::printf("\n");
    }
}

}  // namespace

int main(int argc, char** argv) {
    std::string file;
    support::CommandLine cl("throng-inspect",
                            "What the glTF loader makes of a character file: templates, the joint tree, morph\n"
                            "channels, clips, primitives with their morph targets, bounding spheres and warnings.");
    cl.app().add_option("FILE", file, "a .gltf or .glb file")->required()->check(support::existingFile());
    if (const auto code = cl.parse(argc, argv)) return *code;
    CharacterAsset asset;
    try {
        asset = loadCharacter(file);
    } catch (const GltfError& e) {
        std::cerr << e.what() << "\n";
        return 1;
    } catch (const std::exception& e) {
        std::cerr << file << ": /: " << e.what() << "\n";
        return 1;
    }
    std::printf("file: %s\n", asset.source.c_str());
    std::printf("templates: %zu\n", asset.characters.size());
    for (const LoadedCharacter& c : asset.characters) printCharacter(asset, c);
    std::printf("animations: %zu\n", asset.animations.size());
    for (const LoadedAnimation& a : asset.animations)
        std::printf("  %-24s %8.3f s  %d channels (%d loaded)\n", a.name.c_str(), a.duration, a.channels, a.channelsLoaded);
    std::size_t triangles = 0, vertices = 0;
    std::printf("primitives: %zu\n", asset.primitives.size());
    for (const LoadedPrimitive& p : asset.primitives) {
        triangles += p.data->triangleCount();
        vertices += p.data->vertexCount();
        const BoundingSphere b = p.data->computeBound();
        std::printf("  mesh %d #%d node %d%s: %zu triangles, %zu vertices, %s, sphere (%.3g, %.3g, %.3g) r %.3g\n", p.mesh,
                    p.primitive, p.node, p.skin >= 0 ? (" skin " + std::to_string(p.skin)).c_str() : "",
                    p.data->triangleCount(), p.data->vertexCount(),
                    p.data->baseColorTexture ? (std::to_string(p.data->baseColorTexture->width) + "x" +
                                                std::to_string(p.data->baseColorTexture->height) + " texture").c_str()
                                             : "no texture",
                    b.center().x, b.center().y, b.center().z, b.radius());
        if (!p.data->morphTargets.empty()) {
            std::printf("    morph targets:");
            for (const MorphTarget& m : p.data->morphTargets)
                std::printf(" %s%s", m.name.c_str(), m.normals.empty() ? "" : " (+normals)");
            std::printf("\n");
        }
    }
    std::printf("triangles: %zu\nvertices: %zu\n", triangles, vertices);
    std::printf("warnings: %zu\n", asset.warnings.size());
    for (const std::string& w : asset.warnings) std::printf("  %s\n", w.c_str());
    return 0;
}
