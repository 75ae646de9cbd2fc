#include "throng/render/ImpostorBaker.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>

#include "throng/actors/ActorTemplate.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/render/CpuSkinning.h"
#include "throng/render/GlContext.h"
#include "throng/render/GlRenderer.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/MeshDrawable.h"

namespace throng {

struct ImpostorBaker::Impl {
    std::shared_ptr<GlContext> context;
    std::shared_ptr<const ActorTemplate> tmpl;
    const AnimationClip* clip = nullptr;
    ImpostorBakeOptions options;
    ViewHemisphere views;
    std::unique_ptr<GlRenderer> renderer;
    std::vector<std::uint32_t> boneChild;     // node index of each bone's child joint
    glm::vec3 centre{0.0f};
    float radius = 1.0f;
    // Pose workspace.
    std::vector<float> dofs;
    std::vector<Affine> model;
    std::vector<BoundingSphere> geometry, subtree;
    std::vector<std::vector<glm::mat4>> palettes;
    Mat4 rootMatrix{1.0};
    BodyLook look;  // kBakeLook when the figure has body regions: cells white per region

    Impl(const ImpostorBakeOptions& o) : options(o), views(o.azimuths, o.elevations) {}

    // Poses the skeleton at `time` into `model` and `rootMatrix`.
    void pose(double time) {
        const ActorTemplate& t = *tmpl;
        dofs.assign(t.restDofs().begin(), t.restDofs().end());
        clip->sample(t, time, true, {}, dofs);
        rootMatrix = rootPoseMatrix(clip->sampleRoot(time, true));
        model.resize(t.nodeCount());
        computeModelTransforms(t, dofs, {}, model);
    }

    // Every vertex the figure draws at the current pose (actor frame) into `positions`, with the
    // node each one mostly follows into `joints` and the triangles into `triangles` (when given).
    void surface(std::vector<glm::vec3>& positions, std::vector<std::uint32_t>* joints,
                 std::vector<std::array<std::uint32_t, 3>>* triangles) {
        const ActorTemplate& t = *tmpl;
        positions.clear();
        if (joints) joints->clear();
        if (triangles) triangles->clear();
        const auto meshOf = [](const VaLod& lod) -> const MeshData* {
            if (lod.empty()) return nullptr;
            const auto* drawable = dynamic_cast<const MeshDrawable*>(lod.levels().front().drawable.get());
            return drawable ? &drawable->mesh() : nullptr;
        };
        const auto place = [&](const glm::vec3& p) { return glm::vec3(rootMatrix * glm::dvec4(glm::dvec3(p), 1.0)); };
        const auto addTriangles = [&](const MeshData& mesh, std::size_t base) {
            if (!triangles) return;
            for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
                triangles->push_back({static_cast<std::uint32_t>(base + mesh.indices[i]), static_cast<std::uint32_t>(base + mesh.indices[i + 1]),
                                      static_cast<std::uint32_t>(base + mesh.indices[i + 2])});
        };
        if (const MeshData* mesh = meshOf(t.rootGeometry())) {
            const int skinIndex = t.rootGeometry().levels().front().skin;
            const std::size_t base = positions.size();
            if (mesh->skinned() && skinIndex >= 0) {
                const Skin& skin = t.skins()[static_cast<std::size_t>(skinIndex)];
                std::vector<glm::mat4> palette(skin.joints.size());
                computeSkinPalette(t, skin, model, {}, palette);
                std::vector<glm::vec3> skinned(mesh->vertexCount());
                skinMesh(*mesh, palette, skinned, {});
                for (std::size_t v = 0; v < skinned.size(); ++v) {
                    positions.push_back(place(skinned[v]));
                    if (!joints) continue;
                    int dominant = 0;
                    for (int c = 1; c < 4; ++c)
                        if (mesh->weights0[v][c] > mesh->weights0[v][dominant]) dominant = c;
                    const std::size_t joint = mesh->joints0[v][dominant];
                    joints->push_back(joint < skin.joints.size() ? skin.joints[joint] : 0u);
                }
            } else {
                for (const glm::vec3& p : mesh->positions) positions.push_back(place(p));
                if (joints) joints->insert(joints->end(), mesh->vertexCount(), 0u);
            }
            addTriangles(*mesh, base);
        }
        for (std::size_t n = 0; n < t.nodeCount(); ++n)
            if (const MeshData* mesh = meshOf(t.nodes()[n].geometry)) {
                const std::size_t base = positions.size();
                for (const glm::vec3& p : mesh->positions) positions.push_back(place(model[n].transformPoint(p)));
                if (joints) joints->insert(joints->end(), mesh->vertexCount(), static_cast<std::uint32_t>(n));
                addTriangles(*mesh, base);
            }
    }

    Camera camera(std::uint32_t view) const { return camera(views.direction(view)); }

    Camera camera(const glm::vec3& direction) const {
        const glm::dvec3 d = glm::normalize(glm::dvec3(direction));
        const glm::dvec3 c(centre);
        const double r = radius;
        Camera cam;
        cam.setLookAt(c + d * (4.0 * r), c, glm::dvec3(0, 1, 0));
        cam.setProjectionMatrix(glm::ortho(-r, r, -r, r, 0.5 * r, 8.0 * r));
        return cam;
    }

    glm::vec2 toPixel(const Mat4& viewProjection, const glm::dvec3& p) const {
        const glm::dvec4 clipPos = viewProjection * glm::dvec4(p, 1.0);
        const double s = options.cellSize;
        return {static_cast<float>((clipPos.x / clipPos.w * 0.5 + 0.5) * s),
                static_cast<float>((0.5 - 0.5 * clipPos.y / clipPos.w) * s)};
    }
};

ImpostorBaker::ImpostorBaker(std::shared_ptr<GlContext> context, std::shared_ptr<const ActorTemplate> tmpl, int clip,
                             const ImpostorBakeOptions& options) {
    if (!context) throw std::invalid_argument("ImpostorBaker: argument 'context' is null");
    if (!tmpl) throw std::invalid_argument("ImpostorBaker: argument 'tmpl' is null");
    if (clip < 0 || static_cast<std::size_t>(clip) >= tmpl->clips().size())
        throw std::invalid_argument("ImpostorBaker: template '" + tmpl->name() + "' has no clip " + std::to_string(clip));
    if (options.keyframes < 2) throw std::invalid_argument("ImpostorBaker: at least 2 key-frames");
    if (options.cellSize < 8 || options.cellSize > 4096) throw std::invalid_argument("ImpostorBaker: cell size out of range");
    impl_ = std::make_unique<Impl>(options);
    Impl& s = *impl_;
    s.context = std::move(context);
    s.tmpl = std::move(tmpl);
    s.clip = s.tmpl->clips()[static_cast<std::size_t>(clip)].get();
    if (!(s.clip->duration() > 0.0))
        throw std::invalid_argument("ImpostorBaker: clip '" + s.clip->name() + "' has no duration");
    RendererOptions ro;
    ro.width = ro.height = options.cellSize;
    ro.clearColor = glm::vec4(0.0f);
    s.context->makeCurrent();
    s.context->resize(options.cellSize, options.cellSize);
    s.renderer = std::make_unique<GlRenderer>(s.context, ro);

    const ActorTemplate& t = *s.tmpl;
    for (std::size_t i = 0; i < t.nodeCount(); ++i)
        if (t.nodes()[i].parent >= 0) s.boneChild.push_back(static_cast<std::uint32_t>(i));
    // The covered volume: every internal sphere of the figure over finely sampled poses.
    s.geometry.resize(t.nodeCount());
    s.subtree.resize(t.nodeCount());
    BoundingSphere all;
    const int samples = std::max(options.keyframes * 4, 32);
    for (int k = 0; k < samples; ++k) {
        s.pose(s.clip->duration() * k / samples);
        BoundingSphere whole = computeInternalSpheres(t, s.model, {}, s.geometry, s.subtree);
        if (whole.valid()) all.expandBy(whole.transformed(s.rootMatrix));
        for (const Affine& m : s.model) all.expandBy(glm::dvec3(s.rootMatrix * glm::dvec4(glm::dvec3(m.translation), 1.0)));
    }
    if (!all.valid() || !(all.radius() > 0.0)) all = BoundingSphere(Vec3(0.0, 1.0, 0.0), 1.0);
    s.centre = glm::vec3(all.center());
    s.radius = static_cast<float>(all.radius() * 1.02);
    if (hasBodyRegions(t)) s.look = kBakeLook;
}

bool ImpostorBaker::hasBodyRegions(const ActorTemplate& t) {
    const auto regioned = [](const VaLod& lod) {
        for (const VaLodLevel& level : lod.levels()) {
            const auto* drawable = dynamic_cast<const MeshDrawable*>(level.drawable.get());
            if (drawable && !drawable->mesh().regions.empty()) return true;
        }
        return false;
    };
    if (regioned(t.rootGeometry())) return true;
    for (const SkeletonNode& n : t.nodes())
        if (regioned(n.geometry)) return true;
    return false;
}

ImpostorBaker::~ImpostorBaker() = default;

const ViewHemisphere& ImpostorBaker::views() const { return impl_->views; }

Image ImpostorBaker::renderCell(double time, std::uint32_t view) { return renderCell(time, impl_->views.direction(view)); }

Image ImpostorBaker::renderCell(double time, const glm::vec3& toEye) { return render(time, toEye); }

std::vector<std::uint8_t> ImpostorBaker::renderRegions(double time, std::uint32_t view) {
    Impl& s = *impl_;
    RendererOptions ids = s.renderer->options();
    const RendererOptions shaded = ids;
    ids.regionIds = true;
    s.renderer->setOptions(ids);
    Image image;
    try {
        image = render(time, s.views.direction(view));
    } catch (...) {
        s.renderer->setOptions(shaded);
        throw;
    }
    s.renderer->setOptions(shaded);
    const int size = s.options.cellSize;
    const std::size_t texels = static_cast<std::size_t>(size) * static_cast<std::size_t>(size);
    std::vector<std::uint8_t> regions(texels), covered(texels);
    for (std::size_t i = 0; i < texels; ++i) {
        regions[i] = std::min<std::uint8_t>(image.rgba[i * 4], static_cast<std::uint8_t>(kBodyRegionCount));
        covered[i] = image.rgba[i * 4 + 3] > 0;
    }
    // Two texels around the figure take the region of a covered neighbour: a regenerated cell's
    // outline differs a little from the truth's, and its rim should still be recoloured.
    for (int pass = 0; pass < 2; ++pass) {
        const std::vector<std::uint8_t> from = regions, was = covered;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(size) + static_cast<std::size_t>(x);
                if (was[i]) continue;
                for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= size || ny >= size) continue;
                    const std::size_t j = static_cast<std::size_t>(ny) * static_cast<std::size_t>(size) + static_cast<std::size_t>(nx);
                    if (!was[j] || from[j] == 0) continue;
                    regions[i] = from[j];
                    covered[i] = 1;
                    break;
                }
            }
    }
    return regions;
}

Image ImpostorBaker::render(double time, const glm::vec3& toEye) {
    Impl& s = *impl_;
    const ActorTemplate& t = *s.tmpl;
    s.pose(time);
    DrawList list;
    s.palettes.clear();
    s.palettes.reserve(t.rootGeometry().levels().size() + 1);
    const auto addItem = [&](const VaLodLevel& level, const Mat4& world, std::uint32_t part) {
        if (!level.drawable) return;
        DrawItem item;
        item.drawable = level.drawable.get();
        item.world = ItemTransform(world);
        item.part = part;
        item.look = s.look;
        if (level.skin >= 0) {
            const Skin& skin = t.skins()[static_cast<std::size_t>(level.skin)];
            s.palettes.emplace_back(skin.joints.size());
            computeSkinPalette(t, skin, s.model, {}, s.palettes.back());
            item.skinPalette = s.palettes.back().data();
            item.skinPaletteSize = static_cast<std::uint32_t>(skin.joints.size());
        }
        list.add(item, level.drawable->primitiveCount());
    };
    if (!t.rootGeometry().empty()) addItem(t.rootGeometry().levels().front(), s.rootMatrix, 0);
    for (std::size_t i = 0; i < t.nodeCount(); ++i)
        if (!t.nodes()[i].geometry.empty())
            addItem(t.nodes()[i].geometry.levels().front(), s.rootMatrix * s.model[i].toDMat4(), static_cast<std::uint32_t>(i + 1));
    const Camera cam = s.camera(toEye);
    s.context->makeCurrent();
    s.renderer->beginFrame(cam);
    s.renderer->draw(list);
    Image image = s.renderer->readFrame();
    s.renderer->endFrame();
    image.name = t.name() + " t=" + std::to_string(time);
    return image;
}

std::vector<FeatureLine> ImpostorBaker::projectBones(double time, std::uint32_t view) {
    Impl& s = *impl_;
    s.pose(time);
    const Mat4 vp = s.camera(view).viewProjection();
    std::vector<FeatureLine> out;
    out.reserve(s.boneChild.size());
    for (std::uint32_t child : s.boneChild) {
        const auto parent = static_cast<std::size_t>(s.tmpl->nodes()[child].parent);
        const glm::dvec3 a = glm::dvec3(s.rootMatrix * glm::dvec4(glm::dvec3(s.model[parent].translation), 1.0));
        const glm::dvec3 b = glm::dvec3(s.rootMatrix * glm::dvec4(glm::dvec3(s.model[child].translation), 1.0));
        out.push_back({s.toPixel(vp, a), s.toPixel(vp, b)});
    }
    return out;
}

FeatureTrack ImpostorBaker::featureTrack() {
    Impl& s = *impl_;
    const ActorTemplate& t = *s.tmpl;
    const std::size_t bones = s.boneChild.size();
    FeatureTrack track(bones, s.options.keyframes, s.centre, s.radius, s.options.cellSize);
    const auto place = [&](const glm::vec3& p) { return glm::vec3(s.rootMatrix * glm::dvec4(glm::dvec3(p), 1.0)); };
    std::vector<glm::vec3> parents(bones), children(bones);
    for (int k = 0; k < s.options.keyframes; ++k) {
        s.pose(s.clip->duration() * k / s.options.keyframes);
        for (std::size_t i = 0; i < bones; ++i) {
            const auto parent = static_cast<std::size_t>(t.nodes()[s.boneChild[i]].parent);
            parents[i] = place(s.model[parent].translation);
            children[i] = place(s.model[s.boneChild[i]].translation);
        }
        track.setJoints(k, parents, children);
    }

    // Topology: the nodes each bone joins, and limbs: a bone continues its parent bone's limb when
    // that parent node has no other child (no branching between them).
    std::vector<int> childCount(t.nodeCount(), 0);
    for (std::size_t i = 0; i < t.nodeCount(); ++i)
        if (t.nodes()[i].parent >= 0) ++childCount[static_cast<std::size_t>(t.nodes()[i].parent)];
    std::vector<int> boneOfChild(t.nodeCount(), -1);
    for (std::size_t i = 0; i < bones; ++i) boneOfChild[s.boneChild[i]] = static_cast<int>(i);
    std::vector<std::array<std::uint32_t, 2>> nodes(bones);
    std::vector<std::uint32_t> limbs(bones);
    for (std::size_t i = 0; i < bones; ++i) {  // parents come before children: limbs[] of a parent bone is set
        const auto parent = static_cast<std::uint32_t>(t.nodes()[s.boneChild[i]].parent);
        nodes[i] = {parent, s.boneChild[i]};
        const int parentBone = boneOfChild[parent];
        limbs[i] = parentBone >= 0 && childCount[parent] == 1 ? limbs[static_cast<std::size_t>(parentBone)] : static_cast<std::uint32_t>(i);
    }
    track.setTopology(std::move(nodes), std::move(limbs));

    // Radii: each vertex (in the first pose) belongs to its dominant joint; it is measured from the
    // nearest bone leaving that joint (or, for a joint with no child, the bone ending there).
    s.pose(0.0);
    std::vector<std::vector<float>> distances(bones);
    const auto assign = [&](std::uint32_t joint, const glm::vec3& vertex) {
        int best = -1;
        float bestDistance = 0.0f;
        for (int pass = 0; pass < 2 && best < 0; ++pass)
            for (std::size_t i = 0; i < bones; ++i) {
                const std::uint32_t n = pass == 0 ? static_cast<std::uint32_t>(t.nodes()[s.boneChild[i]].parent) : s.boneChild[i];
                if (n != joint) continue;
                const glm::vec3 a = place(s.model[static_cast<std::size_t>(t.nodes()[s.boneChild[i]].parent)].translation);
                const glm::vec3 b = place(s.model[s.boneChild[i]].translation);
                const glm::vec3 ab = b - a;
                const float len2 = glm::dot(ab, ab);
                const float u = len2 > 0.0f ? std::clamp(glm::dot(vertex - a, ab) / len2, 0.0f, 1.0f) : 0.0f;
                const float d = glm::length(vertex - (a + u * ab));
                if (best < 0 || d < bestDistance) best = static_cast<int>(i), bestDistance = d;
            }
        if (best >= 0) distances[static_cast<std::size_t>(best)].push_back(bestDistance);
    };
    std::vector<glm::vec3> vertices;
    std::vector<std::uint32_t> owners;
    s.surface(vertices, &owners, nullptr);
    for (std::size_t v = 0; v < vertices.size(); ++v) assign(owners[v], vertices[v]);
    std::vector<float> radii(bones, 0.0f);
    for (std::size_t i = 0; i < bones; ++i) {
        std::vector<float>& d = distances[i];
        if (d.empty()) continue;
        std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
        radii[i] = d[d.size() / 2];
    }
    track.setRadii(std::move(radii));
    return track;
}

ProxyMesh ImpostorBaker::proxyMesh(std::size_t maxVertices, int samplesPerKeyframe) {
    if (samplesPerKeyframe < 1)
        throw std::invalid_argument("ImpostorBaker::proxyMesh: samplesPerKeyframe must be >= 1, got " + std::to_string(samplesPerKeyframe));
    Impl& s = *impl_;
    std::vector<glm::vec3> positions;
    std::vector<std::uint32_t> joints;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    s.pose(0.0);
    s.surface(positions, &joints, &triangles);
    // Vertex clustering: vertices of one joint within one grid cell (first pose) merge into the one
    // nearest their mean; the grid is refined until the clusters fit maxVertices.
    std::vector<std::uint32_t> cluster(positions.size());
    std::vector<std::uint32_t> representative;
    const auto clusterWith = [&](float cell) {
        std::map<std::tuple<std::uint32_t, int, int, int>, std::uint32_t> ids;
        for (std::size_t v = 0; v < positions.size(); ++v) {
            const glm::vec3 g = glm::floor(positions[v] / cell);
            const auto key = std::make_tuple(joints[v], static_cast<int>(g.x), static_cast<int>(g.y), static_cast<int>(g.z));
            cluster[v] = ids.emplace(key, static_cast<std::uint32_t>(ids.size())).first->second;
        }
        return ids.size();
    };
    std::size_t count = positions.size();
    if (maxVertices > 0 && positions.size() > maxVertices) {
        float lo = 1e-5f * s.radius, hi = 2.0f * s.radius;
        for (int i = 0; i < 24; ++i) {
            const float mid = std::sqrt(lo * hi);
            if (clusterWith(mid) > maxVertices) lo = mid;
            else hi = mid;
        }
        count = clusterWith(hi);
        std::vector<glm::vec3> mean(count, glm::vec3(0.0f));
        std::vector<int> members(count, 0);
        for (std::size_t v = 0; v < positions.size(); ++v) mean[cluster[v]] += positions[v], ++members[cluster[v]];
        representative.assign(count, 0);
        std::vector<float> best(count, std::numeric_limits<float>::infinity());
        for (std::size_t v = 0; v < positions.size(); ++v) {
            const float d = glm::length(positions[v] - mean[cluster[v]] / static_cast<float>(members[cluster[v]]));
            if (d < best[cluster[v]]) best[cluster[v]] = d, representative[cluster[v]] = static_cast<std::uint32_t>(v);
        }
    } else {
        // Only weld copies of one vertex (split for texture seams or normals): same joint, same
        // place to a micrometre.
        count = clusterWith(1e-6f);
        representative.assign(count, 0);
        for (std::size_t v = positions.size(); v-- > 0;) representative[cluster[v]] = static_cast<std::uint32_t>(v);
    }
    std::vector<std::array<std::uint32_t, 3>> kept;
    for (const auto& t : triangles) {
        const std::array<std::uint32_t, 3> c{cluster[t[0]], cluster[t[1]], cluster[t[2]]};
        if (c[0] != c[1] && c[1] != c[2] && c[0] != c[2]) kept.push_back(c);
    }
    const int poses = s.options.keyframes * samplesPerKeyframe;
    ProxyMesh proxy(count, poses, s.centre, s.radius, s.options.cellSize);
    proxy.setTriangles(std::move(kept));
    std::vector<glm::vec3> keyed(count);
    for (int k = 0; k < poses; ++k) {
        s.pose(s.clip->duration() * k / poses);
        s.surface(positions, nullptr, nullptr);
        for (std::size_t c = 0; c < count; ++c) keyed[c] = positions[representative[c]];
        proxy.setPositions(k, keyed);
    }
    return proxy;
}

ImpostorAtlas ImpostorBaker::bake() {
    Impl& s = *impl_;
    const ActorTemplate& t = *s.tmpl;
    std::vector<std::string> names;
    for (std::uint32_t child : s.boneChild) names.push_back(t.nodes()[child].name);
    ImpostorAtlas atlas(t.name(), s.clip->name(), s.views, s.options.keyframes, s.clip->duration(), s.options.cellSize, names);
    atlas.setWorldBounds(s.centre, s.radius);
    // Bone importance: length in the rest pose (long bones move the most pixels).
    s.pose(0.0);
    std::vector<float> importance;
    for (std::uint32_t child : s.boneChild) importance.push_back(glm::length(s.model[child].translation - s.model[static_cast<std::size_t>(t.nodes()[child].parent)].translation));
    atlas.setBoneImportance(importance);
    for (int k = 0; k < s.options.keyframes; ++k) {
        const double time = s.clip->duration() * k / s.options.keyframes;
        for (std::uint32_t v = 0; v < s.views.viewCount(); ++v) {
            atlas.setCell(v, k, renderCell(time, v));
            if (s.look.any()) atlas.setRegions(v, k, renderRegions(time, v));
            const std::vector<FeatureLine> lines = projectBones(time, v);
            std::copy(lines.begin(), lines.end(), atlas.lines(v, k).begin());
        }
        if (s.options.progress) s.options.progress(k + 1, s.options.keyframes);
    }
    return atlas;
}

}  // namespace throng
