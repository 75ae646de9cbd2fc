// The template of one glTF skin. See SkinTemplateBuilder.h for the steps.

#include "SkinTemplateBuilder.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_inverse.hpp>

#include "JsonPointer.h"
#include "SkinnedMeshMerger.h"
#include "throng/actors/BodyRegions.h"
#include "throng/gltf/MeshSimplifier.h"
#include "throng/scenegraph/MeshDrawable.h"

namespace throng::gltf {
namespace {

// Skeletal LOD from the mesh: a node switches off at the distance where the part it moves (the
// bind-pose vertices it and its descendants dominate) subtends less than `angle` radians. Nodes
// holding rigid geometry, and their ancestors, stay on (vaLod validation would refuse otherwise),
// and so do the roots.
// A part holds its descendants' parts, so a child never outlives its parent.
void deactivateSmallParts(std::vector<SkeletonNode>& nodes, std::vector<BoundingSphere> part, double angle) {
    constexpr double kNearest = 0.5;  // metres: a part with no vertex is off beyond this
    std::vector<char> keep(nodes.size(), 0);
    for (std::size_t i = nodes.size(); i-- > 0;) {
        keep[i] = keep[i] || !nodes[i].geometry.empty();
        const int p = nodes[i].parent;
        if (p < 0) continue;
        if (part[i].valid()) part[static_cast<std::size_t>(p)].expandBy(part[i]);
        keep[static_cast<std::size_t>(p)] = keep[static_cast<std::size_t>(p)] || keep[i];
    }
    // A root stays on: a joint switched off follows its nearest active ancestor, and with none the
    // skin would fall back to its bind space, without the root's placement and scale (a 0.01-scaled
    // Fox drawn a hundred times too large). Far actors get cheaper through vaLod and impostors.
    for (std::size_t i = 0; i < nodes.size(); ++i) keep[i] = keep[i] || nodes[i].parent < 0;
    for (std::size_t i = 0; i < nodes.size(); ++i)
        nodes[i].deactivationDistance = keep[i] ? std::numeric_limits<double>::infinity()
                                                : std::max(kNearest, part[i].valid() ? 2.0 * part[i].radius() / angle : 0.0);
}

// The template's name: the asset's, with the skin's when the file has several skins.
std::string templateName(const tinygltf::Model& m, const std::string& name, int s) {
    if (m.skins.size() <= 1) return name;
    const std::string& skinName = m.skins[static_cast<std::size_t>(s)].name;
    return name + "/" + (skinName.empty() ? "skin" + std::to_string(s) : skinName);
}

}  // namespace

SkinTemplateBuilder::SkinTemplateBuilder(GltfDocument& doc, const GltfContent& content,
                                         const std::vector<LoadedAnimation>& animations, const GltfLoadOptions& options,
                                         const std::string& name, int skin)
    : doc_(doc),
      m_(doc.model),
      c_(content),
      animations_(animations),
      options_(options),
      name_(name),
      s_(skin),
      joints_(content.skinJoints[static_cast<std::size_t>(skin)]),
      skinName_(doc.model.skins[static_cast<std::size_t>(skin)].name),
      builder_(templateName(doc.model, name, skin)),
      fold_(doc.model.nodes.size()),
      skeletonOfJoint_(joints_.size(), -1) {
    for (std::size_t k = 0; k < joints_.size(); ++k) jointIndex_[joints_[k]] = static_cast<int>(k);
    out_.character.skin = skin;
    out_.character.jointCount = static_cast<int>(joints_.size());
}

SkinTemplate SkinTemplateBuilder::build() {
    sortPrimitives();
    foldNodes();
    std::shared_ptr<MeshData> mesh;
    if (!skinned_.empty()) {
        mesh = mergeSkinnedPrimitives(doc_, c_.primitives, skinned_, (skinName_.empty() ? name_ : skinName_) + "/skinned",
                                      ptr("/skins", static_cast<std::size_t>(s_)));
        std::vector<BoundingSphere> parts = computeJointSpheres(*mesh);
        if (options_.jointMinAngle > 0.0) deactivateSmallParts(nodes_, std::move(parts), options_.jointMinAngle);
        for (int i : skinned_) out_.character.primitives.push_back(i);
    }
    const int skinIndex = addNodesAndSkin();
    if (mesh) addMeshLevels(mesh, skinIndex);
    addClips();
    buildTemplate();
    return std::move(out_);
}

void SkinTemplateBuilder::sortPrimitives() {
    for (std::size_t i = 0; i < c_.primitives.size(); ++i) {
        const ReadPrimitive& p = c_.primitives[i];
        if (p.skin == s_) {
            skinned_.push_back(static_cast<int>(i));
            continue;
        }
        if (p.skin >= 0) continue;
        for (int a = p.node; a >= 0; a = c_.parent[static_cast<std::size_t>(a)])
            if (jointIndex_.count(a)) {
                rigidUnder_[a].push_back(static_cast<int>(i));
                break;
            }
    }
    for (const auto& [node, list] : rigidUnder_)
        for (int i : list) out_.rigidPrimitives.push_back(i);
}

void SkinTemplateBuilder::foldNodes() {
    // An animated node above a joint moves the joint (glTF: a joint's global transform includes
    // its ancestors'): it becomes a Skeleton node with DOFs, as a joint, instead of being folded.
    std::vector<char> aboveJoint(m_.nodes.size(), 0);
    for (int j : joints_)
        for (int a = c_.parent[static_cast<std::size_t>(j)]; a >= 0; a = c_.parent[static_cast<std::size_t>(a)])
            aboveJoint[static_cast<std::size_t>(a)] = 1;

    int root = joints_[0];
    while (c_.parent[static_cast<std::size_t>(root)] >= 0) root = c_.parent[static_cast<std::size_t>(root)];
    struct Item {
        int node;
        int skeletonParent;
        dmat4 above;  // non-joint transforms since the skeleton parent (or the world origin)
    };
    std::vector<Item> stack{{root, -1, uniformScale(options_.scale)}};
    while (!stack.empty()) {
        Item it = stack.back();
        stack.pop_back();
        const auto n = static_cast<std::size_t>(it.node);
        int skeletonHere = it.skeletonParent;
        dmat4 above = it.above * c_.local[n];
        const bool joint = jointIndex_.count(it.node) > 0;
        if (joint || (aboveJoint[n] && c_.animatedNodes.count(it.node))) {
            skeletonHere = addJointNode(it.node, it.above, it.skeletonParent);
            above = dmat4(1.0);
            extentPoints_.push_back(dvec3(c_.world[n][3]));
            addRigidGeometry(it.node, skeletonHere);
        }
        const auto& children = m_.nodes[n].children;
        for (auto c = children.rbegin(); c != children.rend(); ++c) stack.push_back({*c, skeletonHere, above});
    }
    for (std::size_t k = 0; k < joints_.size(); ++k)
        if (skeletonOfJoint_[k] < 0)
            doc_.fail(ptr(ptr("/skins", static_cast<std::size_t>(s_)) + "/joints", k), "joint not reached from the common root");
}

int SkinTemplateBuilder::addJointNode(int node, const dmat4& above, int skeletonParent) {
    const auto n = static_cast<std::size_t>(node);
    Trs b = decompose(above);
    int parent = skeletonParent;
    if (!nearIdentity(above) && !b.uniform) {
        parent = keepNonUniformScale(node, b, skeletonParent);
        b = Trs{};
    }
    const Trs& j = c_.trs[n];
    SkeletonNode sn;
    sn.name = uniqueName(nodeName(m_, node));
    sn.parent = parent;
    sn.restTranslation = glm::vec3(b.t);
    sn.restRotation = glm::quat(b.r);
    sn.restScale = glm::vec3(b.s.x);
    const dvec3 pos = b.s.x * (b.r * j.t);
    Dof position{DofKind::Position, glm::vec3(0), -INFINITY, INFINITY, {float(pos.x), float(pos.y), float(pos.z), 0}};
    Dof orientation{DofKind::Orientation, glm::vec3(0), -INFINITY, INFINITY, {float(j.r.x), float(j.r.y), float(j.r.z), float(j.r.w)}};
    Dof scale{DofKind::Scale, glm::vec3(0), -INFINITY, INFINITY, {float(j.s.x), float(j.s.y), float(j.s.z), 0}};
    sn.dofs = {position, orientation, scale};
    const auto k = jointIndex_.find(node);
    const bool joint = k != jointIndex_.end();
    if (joint) sn.inverseBind = c_.inverseBinds[static_cast<std::size_t>(s_)][static_cast<std::size_t>(k->second)];
    nodes_.push_back(sn);
    out_.character.nodeSource.push_back(node);
    const int here = static_cast<int>(nodes_.size()) - 1;
    if (joint) skeletonOfJoint_[static_cast<std::size_t>(k->second)] = here;
    fold_[n] = JointFold{here, b.s.x, b.r};
    return here;
}

int SkinTemplateBuilder::keepNonUniformScale(int node, const Trs& above, int skeletonParent) {
    const int holder = c_.parent[static_cast<std::size_t>(node)];
    doc_.warn(ptr("/nodes", static_cast<std::size_t>(holder)),
              std::string("non-uniform scale") + (above.exact ? "" : " with shear (approximated)") + " above '" +
                  nodeName(m_, node) + "' kept as a Skeleton node without DOFs");
    SkeletonNode keep;
    keep.name = uniqueName(nodeName(m_, holder));
    keep.parent = skeletonParent;
    keep.restTranslation = glm::vec3(above.t);
    keep.restRotation = glm::quat(above.r);
    keep.restScale = glm::vec3(above.s);
    nodes_.push_back(keep);
    out_.character.nodeSource.push_back(holder);
    return static_cast<int>(nodes_.size()) - 1;
}

void SkinTemplateBuilder::addRigidGeometry(int node, int skeletonNode) {
    const auto r = rigidUnder_.find(node);
    if (r == rigidUnder_.end()) return;
    const std::string jointName = nodes_[static_cast<std::size_t>(skeletonNode)].name;
    const dmat4 toJoint = glm::inverse(c_.world[static_cast<std::size_t>(node)]);
    for (int pi : r->second) {
        const ReadPrimitive& p = c_.primitives[static_cast<std::size_t>(pi)];
        auto mesh = std::make_shared<MeshData>(*p.world);
        transformMorphTargets(*mesh, toJoint);  // before the normals it reads are transformed
        for (auto& v : mesh->positions) v = glm::vec3(toJoint * glm::dvec4(dvec3(v), 1.0));
        const glm::dmat3 nm = glm::inverseTranspose(glm::dmat3(toJoint));
        for (auto& v : mesh->normals) {
            const dvec3 d = nm * dvec3(v);
            v = glm::length(d) > 0 ? glm::vec3(glm::normalize(d)) : v;
        }
        SkeletonNode g;
        g.name = uniqueName(jointName + "/" + mesh->name);
        g.parent = skeletonNode;
        g.geometry.addLevel(std::numeric_limits<double>::infinity(), std::make_shared<MeshDrawable>(mesh));
        nodes_.push_back(g);
        out_.character.nodeSource.push_back(p.node);
        out_.character.primitives.push_back(pi);
        for (const auto& v : p.world->positions) extentPoints_.push_back(dvec3(v));
    }
}

std::vector<BoundingSphere> SkinTemplateBuilder::computeJointSpheres(const MeshData& mesh) {
    std::vector<BoundingSphere> spheres(joints_.size());
    std::vector<BoundingSphere> parts(nodes_.size());  // bind space, metres: what each node moves
    const auto& ibm = c_.inverseBinds[static_cast<std::size_t>(s_)];
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        const int bestK = static_cast<int>(mesh.strongestJoint(v));
        const glm::dvec4 p = glm::dmat4(ibm[static_cast<std::size_t>(bestK)]) * glm::dvec4(dvec3(mesh.positions[v]), 1.0);
        if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) spheres[static_cast<std::size_t>(bestK)].expandBy(dvec3(p));
        extentPoints_.push_back(options_.scale * dvec3(mesh.positions[v]));  // bind space, scaled
        if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
            parts[static_cast<std::size_t>(skeletonOfJoint_[static_cast<std::size_t>(bestK)])].expandBy(extentPoints_.back());
    }
    for (std::size_t k = 0; k < joints_.size(); ++k)
        nodes_[static_cast<std::size_t>(skeletonOfJoint_[k])].geometrySphere = spheres[k];
    return parts;
}

int SkinTemplateBuilder::addNodesAndSkin() {
    for (SkeletonNode& sn : nodes_) {
        try {
            builder_.addNode(sn);
        } catch (const std::invalid_argument& e) {
            doc_.fail(ptr("/skins", static_cast<std::size_t>(s_)), e.what());
        }
    }
    Skin skin;
    skin.name = skinName_.empty() ? templateName(m_, name_, s_) : skinName_;
    for (int k : skeletonOfJoint_) skin.joints.push_back(static_cast<std::uint32_t>(k));
    return builder_.addSkin(skin);
}

void SkinTemplateBuilder::addMeshLevels(const std::shared_ptr<MeshData>& mesh, int skinIndex) {
    LoadedCharacter& ch = out_.character;
    if (options_.bodyRegions) {
        std::vector<std::string> names;
        for (int k : skeletonOfJoint_) names.push_back(k < 0 ? std::string() : nodes_[static_cast<std::size_t>(k)].name);
        // Heights in the glTF world at rest (its +Y up), whatever frame the mesh itself lies in.
        const auto& joints = c_.skinJoints[static_cast<std::size_t>(s_)];
        std::vector<dmat4> restSkin(joints.size());
        for (std::size_t k = 0; k < joints.size(); ++k)
            restSkin[k] = c_.world[static_cast<std::size_t>(joints[k])] * dmat4(c_.inverseBinds[static_cast<std::size_t>(s_)][k]);
        std::vector<float> height(mesh->vertexCount());
        for (std::size_t v = 0; v < height.size(); ++v) {
            double y = 0.0, total = 0.0;
            for (int c = 0; c < mesh->influenceCount(); ++c) {
                const float w = c < 4 ? mesh->weights0[v][c] : mesh->weights1[v][c - 4];
                const std::size_t k = c < 4 ? mesh->joints0[v][c] : mesh->joints1[v][c - 4];
                if (!(w > 0.0f) || k >= restSkin.size()) continue;
                y += w * (restSkin[k] * glm::dvec4(dvec3(mesh->positions[v]), 1.0)).y;
                total += w;
            }
            height[v] = static_cast<float>(total > 0.0 ? y / total : mesh->positions[v].y);
        }
        try {
            mesh->regions = bodyRegions(*mesh, height, names);
        } catch (const std::invalid_argument& e) {
            doc_.warn(ptr("/skins", static_cast<std::size_t>(s_)), std::string("no body regions: ") + e.what());
        }
    }
    if (options_.lodLevels.empty()) {
        builder_.rootGeometry().addLevel(std::numeric_limits<double>::infinity(), std::make_shared<MeshDrawable>(mesh), skinIndex);
        ch.lodErrors.push_back(0.0);
        return;
    }
    // Coarser levels keep the vertices they use with their influences: they skin alike.
    for (const GltfLodLevel& level : options_.lodLevels) {
        std::shared_ptr<const MeshData> shown = mesh;
        double error = 0.0;
        if (level.triangleShare < 1.0) {
            SimplifiedMesh simple = simplifyMesh(*mesh, level.triangleShare);
            simple.mesh->name = mesh->name + "/lod" + std::to_string(ch.lodErrors.size());
            shown = simple.mesh;
            error = simple.error * options_.scale;
        }
        builder_.rootGeometry().addLevel(level.maxDistance, std::make_shared<MeshDrawable>(shown), skinIndex);
        ch.lodErrors.push_back(error);
    }
}

void SkinTemplateBuilder::addClips() {
    std::set<std::string> clipNames;
    const std::vector<std::string> morphChannels = builder_.morphChannels();
    std::set<int> drawnNodes;  // glTF nodes whose primitives this template draws
    for (int i : out_.character.primitives) drawnNodes.insert(c_.primitives[static_cast<std::size_t>(i)].node);
    for (std::size_t a = 0; a < c_.channels.size(); ++a) {
        std::vector<ClipChannel> out;
        std::set<std::uint32_t> weighted;  // morph channels this clip drives already
        for (const ReadChannel& in : c_.channels[a]) {
            if (in.path == 3) {
                if (!drawnNodes.count(in.node)) continue;  // another template's mesh
                const bool used = addWeightChannels(in, morphChannels, weighted, out);
                if (used) out_.channelsUsed.emplace_back(static_cast<int>(a), in.index);
                continue;
            }
            const JointFold& f = fold_[static_cast<std::size_t>(in.node)];
            if (f.skeleton < 0) continue;  // not a Skeleton node of this template
            out.push_back(clipChannel(in, f, a));
            out_.channelsUsed.emplace_back(static_cast<int>(a), in.index);
        }
        if (out.empty()) continue;
        std::string clipName = animations_[a].name;
        for (int k = 2; clipNames.count(clipName); ++k) clipName = animations_[a].name + "#" + std::to_string(k);
        clipNames.insert(clipName);
        try {
            builder_.addClip(std::make_shared<const AnimationClip>(clipName, std::move(out)));
        } catch (const std::invalid_argument& e) {
            doc_.fail(ptr("/animations", a), e.what());
        }
        out_.character.clipSource.push_back(static_cast<int>(a));
    }
}

bool SkinTemplateBuilder::addWeightChannels(const ReadChannel& in, const std::vector<std::string>& morphChannels,
                                            std::set<std::uint32_t>& weighted, std::vector<ClipChannel>& out) const {
    const int meshIndex = m_.nodes[static_cast<std::size_t>(in.node)].mesh;
    const std::vector<std::string>& names = c_.targetNames[static_cast<std::size_t>(meshIndex)];
    const auto targets = static_cast<std::size_t>(in.targets);
    const std::size_t perKey = in.interpolation == Interpolation::CubicSpline ? 3 : 1;
    bool used = false;
    for (std::size_t k = 0; k < targets && k < names.size(); ++k) {
        const auto found = std::find(morphChannels.begin(), morphChannels.end(), names[k]);
        if (found == morphChannels.end()) continue;
        const auto channel = static_cast<std::uint32_t>(found - morphChannels.begin());
        // Meshes sharing a target name share its weight: the first channel driving it wins.
        if (!weighted.insert(channel).second) continue;
        ClipChannel cc;
        cc.target = ClipChannel::Target::MorphWeight;
        cc.node = channel;
        cc.interpolation = in.interpolation;
        cc.times = *in.times;
        // Per key the file holds every target's value (CUBICSPLINE: in-tangents, values and
        // out-tangents, each for every target); this target's are picked out.
        for (std::size_t key = 0; key < cc.times.size(); ++key)
            for (std::size_t part = 0; part < perKey; ++part) cc.values.push_back((*in.values)[(key * perKey + part) * targets + k]);
        out.push_back(std::move(cc));
        used = true;
    }
    return used;
}

ClipChannel SkinTemplateBuilder::clipChannel(const ReadChannel& in, const JointFold& f, std::size_t a) const {
    ClipChannel cc;
    cc.target = ClipChannel::Target::NodeDof;
    cc.node = static_cast<std::uint32_t>(f.skeleton);
    cc.dof = static_cast<std::uint32_t>(in.path);
    cc.interpolation = in.interpolation;
    cc.times = *in.times;
    cc.values = *in.values;
    if (in.path == 0 && (f.scale != 1.0 || f.rotation != dquat(1, 0, 0, 0)))
        for (std::size_t k = 0; k + 2 < cc.values.size(); k += 3) {
            const dvec3 t = f.scale * (f.rotation * dvec3(cc.values[k], cc.values[k + 1], cc.values[k + 2]));
            cc.values[k] = float(t.x), cc.values[k + 1] = float(t.y), cc.values[k + 2] = float(t.z);
        }
    if (in.path == 1 && in.interpolation != Interpolation::CubicSpline)
        for (std::size_t k = 0; k + 3 < cc.values.size(); k += 4) {
            const double len = std::sqrt(double(cc.values[k]) * cc.values[k] + double(cc.values[k + 1]) * cc.values[k + 1] +
                                         double(cc.values[k + 2]) * cc.values[k + 2] + double(cc.values[k + 3]) * cc.values[k + 3]);
            if (!(len > 1e-6)) doc_.fail(ptr("/animations", a) + "/channels/" + std::to_string(in.index), "key " + std::to_string(k / 4) + " is a zero quaternion");
            for (int q = 0; q < 4; ++q) cc.values[k + static_cast<std::size_t>(q)] = static_cast<float>(cc.values[k + static_cast<std::size_t>(q)] / len);
        }
    return cc;
}

void SkinTemplateBuilder::buildTemplate() {
    const double margin = options_.sklsrootMargin >= 0 ? options_.sklsrootMargin : std::max(0.05, 0.01 * restExtent(extentPoints_));
    try {
        builder_.setSkeletonRootMargin(margin);
        builder_.setRadiusSampleRate(options_.sklsrootSampleRate);
        out_.character.tmpl = builder_.build();
    } catch (const std::invalid_argument& e) {
        doc_.fail(ptr("/skins", static_cast<std::size_t>(s_)), e.what());
    }
}

std::string SkinTemplateBuilder::uniqueName(const std::string& n) {
    std::string u = n;
    for (int k = 2; names_.count(u); ++k) u = n + "#" + std::to_string(k);
    names_.insert(u);
    return u;
}

}  // namespace throng::gltf
