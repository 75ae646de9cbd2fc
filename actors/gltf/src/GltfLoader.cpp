// The glTF character loader: checks the document, folds the node hierarchy into Skeleton nodes (one
// template per skin), merges each skin's primitives into one skinned mesh, and turns animations
// into clips. See GltfLoader.h.

#include "throng/gltf/GltfLoader.h"
#include "throng/gltf/MeshSimplifier.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "AccessorReader.h"
#include "GltfDocument.h"
#include "ImageDecoder.h"
#include "throng/scenegraph/MeshDrawable.h"

namespace throng {

GltfError::GltfError(std::string file, std::string where, std::string problem)
    : std::invalid_argument(file + ": " + where + ": " + problem),
      file_(std::move(file)),
      where_(std::move(where)),
      problem_(std::move(problem)) {}

std::shared_ptr<const ActorTemplate> CharacterAsset::primaryTemplate() const {
    for (const LoadedCharacter& c : characters)
        if (c.skin >= 0) return c.tmpl;
    return characters.empty() ? nullptr : characters.front().tmpl;
}

const LoadedCharacter* CharacterAsset::findCharacter(const std::string& name) const {
    for (const LoadedCharacter& c : characters)
        if (c.tmpl && c.tmpl->name() == name) return &c;
    return nullptr;
}

namespace gltf {
namespace {

// Skeletal LOD from the mesh: a node switches off at the distance where the part it moves (the
// bind-pose vertices it and its descendants dominate) subtends less than `angle` radians. Nodes
// holding rigid geometry, and their ancestors, stay on (vaLod validation would refuse otherwise).
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
    for (std::size_t i = 0; i < nodes.size(); ++i)
        nodes[i].deactivationDistance = keep[i] ? std::numeric_limits<double>::infinity()
                                                : std::max(kNearest, part[i].valid() ? 2.0 * part[i].radius() / angle : 0.0);
}

using glm::dmat4;
using glm::dquat;
using glm::dvec3;

std::string ptr(const std::string& a, std::size_t i) { return a + "/" + std::to_string(i); }

// A transform split as T(t) R(r) S(s), and whether that split is exact (no shear).
struct Trs {
    dvec3 t{0.0};
    dquat r{1.0, 0.0, 0.0, 0.0};
    dvec3 s{1.0};
    bool exact = true;
    bool uniform = true;  // s.x == s.y == s.z > 0 (up to rounding): folds into a joint
};

Trs decompose(const dmat4& m) {
    Trs d;
    d.t = dvec3(m[3]);
    dvec3 c[3] = {dvec3(m[0]), dvec3(m[1]), dvec3(m[2])};
    d.s = dvec3(glm::length(c[0]), glm::length(c[1]), glm::length(c[2]));
    const double det = glm::dot(c[0], glm::cross(c[1], c[2]));
    if (det < 0) d.s.x = -d.s.x;  // a mirror: put it on x
    glm::dmat3 rot(1.0);
    for (int k = 0; k < 3; ++k)
        if (std::abs(d.s[k]) > 1e-12) rot[k] = c[k] / d.s[k];
    const double tol = 1e-5 * std::max({std::abs(d.s.x), std::abs(d.s.y), std::abs(d.s.z), 1e-12});
    d.exact = std::abs(glm::dot(c[0], c[1])) <= tol * std::abs(d.s.x) + 1e-12 &&
              std::abs(glm::dot(c[0], c[2])) <= tol * std::abs(d.s.x) + 1e-12 &&
              std::abs(glm::dot(c[1], c[2])) <= tol * std::abs(d.s.y) + 1e-12 && std::abs(det) > 1e-30;
    d.r = glm::normalize(glm::quat_cast(rot));
    d.uniform = d.exact && d.s.x > 0 && std::abs(d.s.x - d.s.y) <= tol && std::abs(d.s.x - d.s.z) <= tol;
    return d;
}

dmat4 compose(const dvec3& t, const dquat& r, const dvec3& s) {
    dmat4 m = glm::mat4_cast(r);
    m[0] *= s.x, m[1] *= s.y, m[2] *= s.z;
    m[3] = glm::dvec4(t, 1.0);
    return m;
}

bool nearIdentity(const dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (std::abs(m[c][r] - (c == r ? 1.0 : 0.0)) > 1e-9) return false;
    return true;
}

// Linear -> sRGB 8-bit, for palette textures built from base colours.
std::uint8_t toSrgb8(double linear) {
    linear = std::clamp(linear, 0.0, 1.0);
    const double s = linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
    return static_cast<std::uint8_t>(std::lround(s * 255.0));
}

// One primitive read from the file, before it goes to a template.
struct Prim {
    int mesh = -1, primitive = -1, node = -1, skin = -1, material = -1;
    std::shared_ptr<MeshData> local;  // mesh space (skinned: joint indices of the skin)
    std::shared_ptr<const MeshData> world;  // unskinned: world space
    int texture = -1;                       // glTF image drawn, or -1
};

// Where each glTF node sits in a built skeleton.
struct JointFold {
    int skeleton = -1;     // Skeleton node index
    double scale = 1.0;    // a of the folded B = T(b) R(r) S(a)
    dquat rotation{1.0, 0.0, 0.0, 0.0};  // r of the folded B
};

class Loader {
public:
    Loader(GltfDocument& doc, const GltfLoadOptions& options, std::string name)
        : doc_(doc), m_(doc.model), options_(options), reader_(doc, options.limits), name_(std::move(name)) {}

    CharacterAsset run();
    // The uniform scale of GltfLoadOptions::scale as a matrix.
    dmat4 fileScale() const { return glm::scale(dmat4(1.0), dvec3(options_.scale)); }
    // Rejects a scale or LOD levels that make no sense, before any work.
    void checkOptions() const;

private:
    [[noreturn]] void fail(const std::string& where, const std::string& problem) const {
        throw GltfError(doc_.file, where, problem);
    }
    void warn(const std::string& where, const std::string& problem) { doc_.warnings.push_back(where + ": " + problem); }

    void readNodes();
    void readScene();
    void checkSkins();
    void readPrimitives();
    Prim readPrimitive(int nodeIndex, int meshIndex, int p);
    std::shared_ptr<const Image> texture(int imageIndex);
    void readAnimations();
    void buildSkin(int s);
    void buildStatic();
    std::shared_ptr<MeshData> mergeSkinned(int s, const std::vector<int>& prims);
    double restExtent(const std::vector<dvec3>& points) const;
    std::string nodeName(int n) const {
        const std::string& nm = m_.nodes[static_cast<std::size_t>(n)].name;
        return nm.empty() ? "node" + std::to_string(n) : nm;
    }

    GltfDocument& doc_;
    tinygltf::Model& m_;
    const GltfLoadOptions& options_;
    AccessorReader reader_;
    std::string name_;
    CharacterAsset asset_;

    std::vector<int> parent_;
    std::vector<dmat4> local_, world_;
    std::vector<Trs> trs_;
    std::vector<char> inScene_;
    std::vector<int> order_;  // nodes of the scene, depth first
    std::vector<std::vector<int>> skinJoints_;  // per skin: glTF nodes
    std::vector<std::vector<glm::mat4>> ibm_;   // per skin
    std::vector<Prim> prims_;
    std::map<int, std::shared_ptr<const Image>> images_;
    std::set<int> badImages_;
    std::set<int> rigidClaimed_;  // unskinned primitives drawn as a joint's rigid geometry

    // Animations, read once: per animation, per channel: (node, path, times, values, interpolation).
    struct Channel {
        int node = -1;
        int path = 0;  // 0 translation, 1 rotation, 2 scale
        int index = 0; // channel index in the animation
        Interpolation interpolation = Interpolation::Linear;
        std::shared_ptr<const std::vector<float>> times;
        std::shared_ptr<const std::vector<float>> values;
    };
    std::vector<std::vector<Channel>> channels_;
    std::vector<std::set<int>> loadedChannels_;
    std::set<int> animatedNodes_;  // nodes some loaded channel drives
};

void Loader::readNodes() {
    const std::size_t n = m_.nodes.size();
    parent_.assign(n, -1);
    local_.assign(n, dmat4(1.0));
    world_.assign(n, dmat4(1.0));
    trs_.assign(n, Trs{});
    for (std::size_t i = 0; i < n; ++i) {
        const tinygltf::Node& node = m_.nodes[i];
        const std::string where = ptr("/nodes", i);
        for (std::size_t k = 0; k < node.children.size(); ++k) {
            const int c = node.children[k];
            if (c < 0 || static_cast<std::size_t>(c) >= n) fail(ptr(where + "/children", k), "node " + std::to_string(c) + " does not exist");
            if (static_cast<std::size_t>(c) == i) fail(ptr(where + "/children", k), "a node cannot be its own child");
            if (parent_[static_cast<std::size_t>(c)] >= 0)
                fail(ptr(where + "/children", k), "node " + std::to_string(c) + " already has parent " +
                                                       std::to_string(parent_[static_cast<std::size_t>(c)]));
            parent_[static_cast<std::size_t>(c)] = static_cast<int>(i);
        }
        if (node.mesh >= 0 && static_cast<std::size_t>(node.mesh) >= m_.meshes.size()) fail(where + "/mesh", "mesh " + std::to_string(node.mesh) + " does not exist");
        if (node.skin >= 0 && static_cast<std::size_t>(node.skin) >= m_.skins.size()) fail(where + "/skin", "skin " + std::to_string(node.skin) + " does not exist");
        Trs& d = trs_[i];
        if (!node.matrix.empty()) {
            if (node.matrix.size() != 16) fail(where + "/matrix", "must hold 16 numbers");
            dmat4 mat;
            for (int k = 0; k < 16; ++k) {
                if (!std::isfinite(node.matrix[static_cast<std::size_t>(k)])) fail(where + "/matrix", "value " + std::to_string(k) + " is not finite");
                mat[k / 4][k % 4] = node.matrix[static_cast<std::size_t>(k)];
            }
            if (mat[0][3] != 0 || mat[1][3] != 0 || mat[2][3] != 0 || mat[3][3] != 1) fail(where + "/matrix", "is not an affine transform");
            local_[i] = mat;
            d = decompose(mat);
            if (!d.exact) warn(where + "/matrix", "has shear, which animation would lose: decomposed approximately");
        } else {
            auto vec = [&](const std::vector<double>& v, std::size_t size, const char* key) {
                if (!v.empty() && v.size() != size) fail(where + "/" + key, "must hold " + std::to_string(size) + " numbers");
                for (std::size_t k = 0; k < v.size(); ++k)
                    if (!std::isfinite(v[k])) fail(where + "/" + key, "value " + std::to_string(k) + " is not finite");
            };
            vec(node.translation, 3, "translation");
            vec(node.rotation, 4, "rotation");
            vec(node.scale, 3, "scale");
            if (!node.translation.empty()) d.t = dvec3(node.translation[0], node.translation[1], node.translation[2]);
            if (!node.rotation.empty()) {
                const dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
                const double len = glm::length(q);
                if (!(len > 1e-6)) fail(where + "/rotation", "is a zero quaternion");
                d.r = q / len;
            }
            if (!node.scale.empty()) d.s = dvec3(node.scale[0], node.scale[1], node.scale[2]);
            d.uniform = d.s.x > 0 && d.s.x == d.s.y && d.s.x == d.s.z;
            local_[i] = compose(d.t, d.r, d.s);
        }
    }
    // Cycles: with one parent per node, a cycle is a loop no root reaches.
    for (std::size_t i = 0; i < n; ++i) {
        std::size_t steps = 0;
        for (int a = parent_[i]; a >= 0; a = parent_[static_cast<std::size_t>(a)])
            if (++steps > n) fail(ptr("/nodes", i), "is part of a cycle of children");
    }
    // World matrices, parents first.
    std::vector<int> stack;
    for (std::size_t i = 0; i < n; ++i)
        if (parent_[i] < 0) stack.push_back(static_cast<int>(i));
    while (!stack.empty()) {
        const auto i = static_cast<std::size_t>(stack.back());
        stack.pop_back();
        world_[i] = parent_[i] >= 0 ? world_[static_cast<std::size_t>(parent_[i])] * local_[i] : fileScale() * local_[i];
        for (int c : m_.nodes[i].children) stack.push_back(c);
    }
}

void Loader::readScene() {
    const std::size_t n = m_.nodes.size();
    inScene_.assign(n, 0);
    std::vector<int> roots;
    if (!m_.scenes.empty()) {
        int s = m_.defaultScene;
        if (s < 0) s = 0;
        if (static_cast<std::size_t>(s) >= m_.scenes.size()) fail("/scene", "scene " + std::to_string(s) + " does not exist");
        const auto& nodes = m_.scenes[static_cast<std::size_t>(s)].nodes;
        for (std::size_t k = 0; k < nodes.size(); ++k) {
            const int r = nodes[k];
            const std::string where = ptr(ptr("/scenes", static_cast<std::size_t>(s)) + "/nodes", k);
            if (r < 0 || static_cast<std::size_t>(r) >= n) fail(where, "node " + std::to_string(r) + " does not exist");
            if (parent_[static_cast<std::size_t>(r)] >= 0) fail(where, "node " + std::to_string(r) + " is not a root node");
            roots.push_back(r);
        }
    } else {
        for (std::size_t i = 0; i < n; ++i)
            if (parent_[i] < 0) roots.push_back(static_cast<int>(i));
    }
    // Depth first, children in order.
    std::vector<int> stack(roots.rbegin(), roots.rend());
    while (!stack.empty()) {
        const int i = stack.back();
        stack.pop_back();
        if (inScene_[static_cast<std::size_t>(i)]) continue;
        inScene_[static_cast<std::size_t>(i)] = 1;
        order_.push_back(i);
        const auto& ch = m_.nodes[static_cast<std::size_t>(i)].children;
        for (auto it = ch.rbegin(); it != ch.rend(); ++it) stack.push_back(*it);
    }
}

void Loader::checkSkins() {
    const std::size_t n = m_.nodes.size();
    auto rootOf = [&](int i) {
        while (parent_[static_cast<std::size_t>(i)] >= 0) i = parent_[static_cast<std::size_t>(i)];
        return i;
    };
    auto isAncestorOrSelf = [&](int a, int i) {
        for (; i >= 0; i = parent_[static_cast<std::size_t>(i)])
            if (i == a) return true;
        return false;
    };
    skinJoints_.resize(m_.skins.size());
    ibm_.resize(m_.skins.size());
    // Pass 1: references and formats of every skin; pass 2 reads the matrices.
    for (std::size_t s = 0; s < m_.skins.size(); ++s) {
        const tinygltf::Skin& skin = m_.skins[s];
        const std::string where = ptr("/skins", s);
        std::set<int> seen;
        for (std::size_t k = 0; k < skin.joints.size(); ++k) {
            const int j = skin.joints[k];
            if (j < 0 || static_cast<std::size_t>(j) >= n)
                fail(ptr(where + "/joints", k), "node " + std::to_string(j) + " does not exist (" + std::to_string(n) + " nodes)");
            if (!seen.insert(j).second) fail(ptr(where + "/joints", k), "node " + std::to_string(j) + " is listed twice");
        }
        if (skin.joints.size() > 65535) fail(where + "/joints", "more than 65535 joints");
        const int root = rootOf(skin.joints[0]);
        for (int j : skin.joints)
            if (rootOf(j) != root) fail(where + "/joints", "joints do not have a common root");
        if (skin.skeleton >= 0) {
            if (static_cast<std::size_t>(skin.skeleton) >= n) fail(where + "/skeleton", "node " + std::to_string(skin.skeleton) + " does not exist");
            for (int j : skin.joints)
                if (!isAncestorOrSelf(skin.skeleton, j))
                    fail(where + "/skeleton", "node " + std::to_string(skin.skeleton) + " is not a common root of the joints");
        }
        if (skin.inverseBindMatrices >= 0) {
            const auto& a = reader_.accessor(skin.inverseBindMatrices, where + "/inverseBindMatrices");
            if (a.type != TINYGLTF_TYPE_MAT4 || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
                fail(where + "/inverseBindMatrices", "accessor must be MAT4 of FLOAT");
            if (a.count < skin.joints.size())
                fail(where + "/inverseBindMatrices", "accessor holds " + std::to_string(a.count) + " matrices for " +
                                                         std::to_string(skin.joints.size()) + " joints");
        }
        skinJoints_[s] = skin.joints;
    }
    for (std::size_t s = 0; s < m_.skins.size(); ++s) {
        const tinygltf::Skin& skin = m_.skins[s];
        const std::string where = ptr("/skins", s) + "/inverseBindMatrices";
        ibm_[s].assign(skin.joints.size(), glm::mat4(1.0f));
        if (skin.inverseBindMatrices < 0) continue;
        const auto& a = m_.accessors[static_cast<std::size_t>(skin.inverseBindMatrices)];
        if (a.bufferView < 0 && !a.sparse.isSparse) {
            warn(where, "accessor holds no data: identity matrices used");
            continue;
        }
        if (m_.bufferViews.size() > static_cast<std::size_t>(std::max(a.bufferView, 0)) && a.bufferView >= 0 &&
            m_.bufferViews[static_cast<std::size_t>(a.bufferView)].byteStride != 0)
            fail(where, "the buffer view of inverse bind matrices must not have a byteStride");
        const auto v = reader_.readNumbers(skin.inverseBindMatrices, where, false);
        for (std::size_t k = 0; k < skin.joints.size(); ++k) {
            const double* e = v.values.data() + k * 16;
            if (e[3] != 0 || e[7] != 0 || e[11] != 0 || e[15] != 1)
                fail(where, "matrix " + std::to_string(k) + " is not affine (last row must be 0 0 0 1)");
            for (int c = 0; c < 16; ++c) ibm_[s][k][c / 4][c % 4] = static_cast<float>(e[c]);
        }
    }
    // Skinned mesh nodes: what glTF ignores, and joints that must be in the same scene.
    bool anyScene = !m_.scenes.empty();
    std::vector<char> used(m_.skins.size(), 0);
    for (std::size_t i = 0; i < n; ++i) {
        const tinygltf::Node& node = m_.nodes[i];
        if (node.skin < 0) continue;
        const std::string where = ptr("/nodes", i);
        if (node.mesh < 0) {
            warn(where, "has a skin but no mesh: skin ignored for it");
            continue;
        }
        used[static_cast<std::size_t>(node.skin)] = 1;
        if (anyScene && inScene_[i])
            for (int j : skinJoints_[static_cast<std::size_t>(node.skin)])
                if (!inScene_[static_cast<std::size_t>(j)])
                    fail(where, "its skin " + std::to_string(node.skin) + " has joint " + std::to_string(j) +
                                    " which is not in the scene that shows this node");
        if (!nearIdentity(local_[i])) warn(where, "local transform of a skinned mesh node is ignored (glTF skinning)");
        bool parentTransform = false;
        for (int a = parent_[i]; a >= 0; a = parent_[static_cast<std::size_t>(a)])
            if (!nearIdentity(local_[static_cast<std::size_t>(a)])) parentTransform = true;
        if (parentTransform) warn(where, "transforms of its parent nodes are ignored for the skinned mesh (glTF skinning)");
    }
    for (std::size_t s = 0; s < m_.skins.size(); ++s)
        if (!used[s]) warn(ptr("/skins", s), "no mesh uses the skin: its template has joints only");
}

std::shared_ptr<const Image> Loader::texture(int imageIndex) {
    if (!options_.decodeImages || badImages_.count(imageIndex)) return nullptr;
    if (auto it = images_.find(imageIndex); it != images_.end()) return it->second;
    const tinygltf::Image& img = m_.images[static_cast<std::size_t>(imageIndex)];
    const std::string where = ptr("/images", static_cast<std::size_t>(imageIndex));
    if (img.image.empty()) {
        warn(where, "image data could not be read" + (img.uri.empty() ? std::string() : " ('" + img.uri + "')") + ": no texture");
        badImages_.insert(imageIndex);
        return nullptr;
    }
    std::string problem;
    const std::string name = img.uri.empty() ? (img.name.empty() ? "image" + std::to_string(imageIndex) : img.name) : img.uri;
    auto decoded = decodeImage(img.image, name, options_.limits.maxImagePixels, problem);
    if (!decoded) {
        warn(where, problem + ": no texture");
        badImages_.insert(imageIndex);
        return nullptr;
    }
    auto shared = std::make_shared<const Image>(std::move(*decoded));
    images_[imageIndex] = shared;
    return shared;
}

Prim Loader::readPrimitive(int nodeIndex, int meshIndex, int p) {
    const tinygltf::Primitive& prim = m_.meshes[static_cast<std::size_t>(meshIndex)].primitives[static_cast<std::size_t>(p)];
    const std::string where = ptr(ptr("/meshes", static_cast<std::size_t>(meshIndex)) + "/primitives", static_cast<std::size_t>(p));
    const int skin = m_.nodes[static_cast<std::size_t>(nodeIndex)].skin;
    Prim out;
    out.mesh = meshIndex, out.primitive = p, out.node = nodeIndex, out.skin = skin, out.material = prim.material;
    auto mesh = std::make_shared<MeshData>();
    const std::string& meshName = m_.meshes[static_cast<std::size_t>(meshIndex)].name;
    mesh->name = (meshName.empty() ? "mesh" + std::to_string(meshIndex) : meshName) + "#" + std::to_string(p);
    auto attr = [&](const char* key) {
        const auto it = prim.attributes.find(key);
        return it == prim.attributes.end() ? -1 : it->second;
    };
    const int position = attr("POSITION");
    if (position < 0) fail(where + "/attributes", "has no POSITION");
    const std::string at = where + "/attributes/";
    const auto pos = reader_.readNumbers(position, at + "POSITION");
    if (pos.width != 3 || reader_.accessor(position, at + "POSITION").type != TINYGLTF_TYPE_VEC3) fail(at + "POSITION", "must be VEC3");
    const std::size_t count = pos.count;
    for (std::size_t v = 0; v < count; ++v)
        mesh->positions.emplace_back(pos.values[v * 3], pos.values[v * 3 + 1], pos.values[v * 3 + 2]);
    auto sameCount = [&](const std::string& key, std::size_t c, int width, int expected) {
        if (c != count) fail(at + key, "holds " + std::to_string(c) + " elements, POSITION holds " + std::to_string(count));
        if (width != expected) fail(at + key, "has " + std::to_string(width) + " components, expected " + std::to_string(expected));
    };
    if (const int normal = attr("NORMAL"); normal >= 0) {
        const auto nv = reader_.readNumbers(normal, at + "NORMAL");
        sameCount("NORMAL", nv.count, nv.width, 3);
        for (std::size_t v = 0; v < count; ++v) mesh->normals.emplace_back(nv.values[v * 3], nv.values[v * 3 + 1], nv.values[v * 3 + 2]);
    }
    // Material: base colour and its texture.
    int texCoord = 0;
    if (prim.material >= 0) {
        if (static_cast<std::size_t>(prim.material) >= m_.materials.size())
            fail(where + "/material", "material " + std::to_string(prim.material) + " does not exist");
        const auto& pbr = m_.materials[static_cast<std::size_t>(prim.material)].pbrMetallicRoughness;
        const std::string mw = ptr("/materials", static_cast<std::size_t>(prim.material)) + "/pbrMetallicRoughness";
        if (pbr.baseColorFactor.size() == 4) {
            for (int c = 0; c < 4; ++c) {
                const double f = pbr.baseColorFactor[static_cast<std::size_t>(c)];
                if (!std::isfinite(f)) fail(mw + "/baseColorFactor", "value " + std::to_string(c) + " is not finite");
                mesh->baseColor[c] = static_cast<float>(f);
            }
        }
        if (pbr.baseColorTexture.index >= 0) {
            const int t = pbr.baseColorTexture.index;
            if (static_cast<std::size_t>(t) >= m_.textures.size())
                fail(mw + "/baseColorTexture/index", "texture " + std::to_string(t) + " does not exist");
            const int source = m_.textures[static_cast<std::size_t>(t)].source;
            if (source >= 0) {
                if (static_cast<std::size_t>(source) >= m_.images.size())
                    fail(ptr("/textures", static_cast<std::size_t>(t)) + "/source", "image " + std::to_string(source) + " does not exist");
                texCoord = pbr.baseColorTexture.texCoord;
                out.texture = source;
            } else {
                warn(ptr("/textures", static_cast<std::size_t>(t)), "has no source image (an extension we do not read?): no texture");
            }
        }
    }
    if (out.texture >= 0) {
        const std::string key = "TEXCOORD_" + std::to_string(texCoord);
        const int uv = attr(key.c_str());
        if (uv < 0) {
            warn(where, "its material's texture uses " + key + ", which it lacks: no texture");
            out.texture = -1;
        } else {
            const auto tv = reader_.readNumbers(uv, at + key);
            sameCount(key, tv.count, tv.width, 2);
            for (std::size_t v = 0; v < count; ++v) mesh->texcoords.emplace_back(tv.values[v * 2], tv.values[v * 2 + 1]);
            mesh->baseColorTexture = texture(out.texture);
            if (!mesh->baseColorTexture) {
                out.texture = -1;
                mesh->texcoords.clear();
            }
        }
    }
    // Triangles.
    std::vector<std::uint32_t> idx;
    if (prim.indices >= 0) {
        const auto iv = reader_.readUnsigned(prim.indices, where + "/indices");
        if (iv.width != 1) fail(where + "/indices", "accessor must be SCALAR");
        for (std::size_t k = 0; k < iv.values.size(); ++k)
            if (iv.values[k] >= count)
                fail(where + "/indices", "index " + std::to_string(k) + " is " + std::to_string(iv.values[k]) + ", beyond the " +
                                             std::to_string(count) + " vertices");
        idx = iv.values;
    } else {
        idx.resize(count);
        for (std::size_t v = 0; v < count; ++v) idx[v] = static_cast<std::uint32_t>(v);
    }
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (idx.size() % 3 != 0) fail(where, std::to_string(idx.size()) + " indices do not make whole triangles");
        mesh->indices = std::move(idx);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        for (std::size_t k = 2; k < idx.size(); ++k) {
            if (mode == TINYGLTF_MODE_TRIANGLE_FAN) mesh->indices.insert(mesh->indices.end(), {idx[0], idx[k - 1], idx[k]});
            else if (k % 2 == 0) mesh->indices.insert(mesh->indices.end(), {idx[k - 2], idx[k - 1], idx[k]});
            else mesh->indices.insert(mesh->indices.end(), {idx[k - 1], idx[k - 2], idx[k]});
        }
    } else {
        warn(where + "/mode", "points and lines are not drawn: primitive skipped");
        return Prim{};
    }
    // Skin influences: every JOINTS_n / WEIGHTS_n set, the largest eight kept.
    if (skin >= 0) {
        const std::size_t joints = skinJoints_[static_cast<std::size_t>(skin)].size();
        std::vector<std::vector<std::pair<float, std::uint32_t>>> infl(count);
        int sets = 0;
        for (int set = 0;; ++set) {
            const std::string jk = "JOINTS_" + std::to_string(set), wk = "WEIGHTS_" + std::to_string(set);
            const int ja = attr(jk.c_str()), wa = attr(wk.c_str());
            if (ja < 0 && wa < 0) break;
            if (ja < 0 || wa < 0) fail(at + (ja < 0 ? jk : wk), "is missing while " + (ja < 0 ? wk : jk) + " is given");
            const auto jv = reader_.readUnsigned(ja, at + jk);
            const auto wv = reader_.readNumbers(wa, at + wk);
            sameCount(jk, jv.count, jv.width, 4);
            sameCount(wk, wv.count, wv.width, 4);
            for (std::size_t v = 0; v < count; ++v)
                for (int c = 0; c < 4; ++c) {
                    const std::uint32_t j = jv.values[v * 4 + static_cast<std::size_t>(c)];
                    const double w = wv.values[v * 4 + static_cast<std::size_t>(c)];
                    if (w < 0) fail(at + wk, "vertex " + std::to_string(v) + " has a negative weight");
                    if (w == 0) continue;
                    if (j >= joints)
                        fail(at + jk, "vertex " + std::to_string(v) + " names joint " + std::to_string(j) + " but skin " +
                                          std::to_string(skin) + " has " + std::to_string(joints));
                    auto& list = infl[v];
                    auto same = std::find_if(list.begin(), list.end(), [&](const auto& e) { return e.second == j; });
                    if (same != list.end()) same->first += static_cast<float>(w);
                    else list.emplace_back(static_cast<float>(w), j);
                }
            ++sets;
        }
        if (sets == 0) fail(at.substr(0, at.size() - 1), "the node has a skin but the primitive has no JOINTS_0 / WEIGHTS_0");
        std::size_t zero = 0, unnormalised = 0, dropped = 0;
        bool eight = false;
        for (auto& list : infl) {
            std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) {
                return a.first != b.first ? a.first > b.first : a.second < b.second;
            });
            if (list.size() > 8) {
                ++dropped;
                list.resize(8);
            }
            eight = eight || list.size() > 4;
            double sum = 0;
            for (const auto& e : list) sum += e.first;
            if (list.empty() || !(sum > 0)) {
                ++zero;
                list.assign(1, {1.0f, 0u});
                sum = 1;
            } else if (std::abs(sum - 1.0) > 0.002 || dropped) {
                ++unnormalised;
            }
            for (auto& e : list) e.first = static_cast<float>(e.first / sum);
        }
        if (zero) warn(at + "WEIGHTS_0", std::to_string(zero) + " vertices have no weight: bound to the skin's first joint");
        if (dropped) warn(at + "JOINTS_0", std::to_string(dropped) + " vertices have more than 8 influences: the 8 largest kept");
        if (unnormalised) warn(at + "WEIGHTS_0", std::to_string(unnormalised) + " vertices have weights not summing to 1: normalised");
        mesh->joints0.assign(count, glm::u16vec4(0));
        mesh->weights0.assign(count, glm::vec4(0));
        if (eight) {
            mesh->joints1.assign(count, glm::u16vec4(0));
            mesh->weights1.assign(count, glm::vec4(0));
        }
        for (std::size_t v = 0; v < count; ++v)
            for (std::size_t k = 0; k < infl[v].size(); ++k) {
                auto& j = k < 4 ? mesh->joints0[v] : mesh->joints1[v];
                auto& w = k < 4 ? mesh->weights0[v] : mesh->weights1[v];
                j[static_cast<int>(k % 4)] = static_cast<std::uint16_t>(infl[v][k].second);
                w[static_cast<int>(k % 4)] = infl[v][k].first;
            }
    }
    out.local = mesh;
    if (skin < 0) {
        // World space: the node's world matrix (normals by its inverse transpose; mirrors flip winding).
        auto w = std::make_shared<MeshData>(*mesh);
        const dmat4& mw = world_[static_cast<std::size_t>(nodeIndex)];
        const glm::dmat3 nm = glm::inverseTranspose(glm::dmat3(mw));
        for (auto& p3 : w->positions) p3 = glm::vec3(mw * glm::dvec4(dvec3(p3), 1.0));
        for (auto& n3 : w->normals) {
            const dvec3 d = nm * dvec3(n3);
            const double len = glm::length(d);
            n3 = len > 0 ? glm::vec3(d / len) : glm::vec3(0, 1, 0);
        }
        if (glm::determinant(glm::dmat3(mw)) < 0)
            for (std::size_t k = 0; k + 2 < w->indices.size(); k += 3) std::swap(w->indices[k + 1], w->indices[k + 2]);
        out.world = w;
    }
    try {
        out.local->validate();
    } catch (const std::invalid_argument& e) {
        fail(where, e.what());
    }
    return out;
}

void Loader::readPrimitives() {
    for (int n : order_) {
        const tinygltf::Node& node = m_.nodes[static_cast<std::size_t>(n)];
        if (node.mesh < 0) continue;
        const auto& mesh = m_.meshes[static_cast<std::size_t>(node.mesh)];
        if (mesh.primitives.empty()) warn(ptr("/meshes", static_cast<std::size_t>(node.mesh)) + "/primitives", "is empty");
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            Prim prim = readPrimitive(n, node.mesh, static_cast<int>(p));
            if (!prim.local) continue;
            if (prim.local->indices.empty()) {
                warn(ptr(ptr("/meshes", static_cast<std::size_t>(node.mesh)) + "/primitives", p), "has no triangle: skipped");
                continue;
            }
            prims_.push_back(prim);
            LoadedPrimitive lp;
            lp.mesh = prim.mesh, lp.primitive = prim.primitive, lp.node = prim.node, lp.skin = prim.skin, lp.material = prim.material;
            lp.data = prim.world ? prim.world : std::shared_ptr<const MeshData>(prim.local);
            asset_.primitives.push_back(lp);
        }
    }
}

void Loader::readAnimations() {
    // Joints, and the nodes above them: their transforms are part of the joints' global transforms.
    std::vector<char> drivesJoint(m_.nodes.size(), 0);
    for (const auto& joints : skinJoints_)
        for (int j : joints)
            for (int a = j; a >= 0 && !drivesJoint[static_cast<std::size_t>(a)]; a = parent_[static_cast<std::size_t>(a)])
                drivesJoint[static_cast<std::size_t>(a)] = 1;
    channels_.resize(m_.animations.size());
    loadedChannels_.resize(m_.animations.size());
    for (std::size_t a = 0; a < m_.animations.size(); ++a) {
        const tinygltf::Animation& anim = m_.animations[a];
        const std::string where = ptr("/animations", a);
        LoadedAnimation info;
        info.name = anim.name.empty() ? "animation" + std::to_string(a) : anim.name;
        info.channels = static_cast<int>(anim.channels.size());
        std::map<int, std::pair<std::shared_ptr<const std::vector<float>>, std::shared_ptr<const std::vector<float>>>> samplers;
        for (std::size_t c = 0; c < anim.channels.size(); ++c) {
            const tinygltf::AnimationChannel& ch = anim.channels[c];
            const std::string cw = ptr(where + "/channels", c);
            if (ch.sampler < 0 || static_cast<std::size_t>(ch.sampler) >= anim.samplers.size())
                fail(cw + "/sampler", "sampler " + std::to_string(ch.sampler) + " does not exist");
            if (ch.target_node < 0) {
                warn(cw + "/target", "has no node: ignored");
                continue;
            }
            if (static_cast<std::size_t>(ch.target_node) >= m_.nodes.size())
                fail(cw + "/target/node", "node " + std::to_string(ch.target_node) + " does not exist");
            int path = -1;
            if (ch.target_path == "translation") path = 0;
            else if (ch.target_path == "rotation") path = 1;
            else if (ch.target_path == "scale") path = 2;
            else if (ch.target_path == "weights") {
                warn(cw + "/target/path", "morph target weights are not supported: ignored");
                continue;
            } else {
                fail(cw + "/target/path", "unknown path '" + ch.target_path + "'");
            }
            if (!drivesJoint[static_cast<std::size_t>(ch.target_node)]) {
                // Only joints and the nodes above them become Skeleton nodes; the data of such
                // channels is not even read.
                warn(cw, "animates node " + std::to_string(ch.target_node) + ", which is not a joint of any skin nor above one: ignored");
                continue;
            }
            const tinygltf::AnimationSampler& s = anim.samplers[static_cast<std::size_t>(ch.sampler)];
            const std::string sw = ptr(where + "/samplers", static_cast<std::size_t>(ch.sampler));
            Channel out;
            out.node = ch.target_node;
            out.path = path;
            out.index = static_cast<int>(c);
            if (s.interpolation == "LINEAR") out.interpolation = Interpolation::Linear;
            else if (s.interpolation == "STEP") out.interpolation = Interpolation::Step;
            else if (s.interpolation == "CUBICSPLINE") out.interpolation = Interpolation::CubicSpline;
            else fail(sw + "/interpolation", "unknown interpolation '" + s.interpolation + "'");
            auto& cached = samplers[ch.sampler];
            if (!cached.first) {
                const auto in = reader_.readNumbers(s.input, sw + "/input", false);
                if (in.width != 1) fail(sw + "/input", "accessor must be SCALAR");
                auto times = std::make_shared<std::vector<float>>();
                for (std::size_t k = 0; k < in.count; ++k) {
                    const double t = in.values[k];
                    if (t < 0) fail(sw + "/input", "key " + std::to_string(k) + " has a negative time");
                    if (t > options_.limits.maxClipDuration)
                        fail(sw + "/input", "key " + std::to_string(k) + " at " + std::to_string(t) + " s exceeds the clip duration limit");
                    if (k > 0 && !(static_cast<float>(t) > times->back()))
                        fail(sw + "/input", "key times are not strictly increasing at key " + std::to_string(k));
                    times->push_back(static_cast<float>(t));
                }
                const auto outv = reader_.readNumbers(s.output, sw + "/output", false);
                auto values = std::make_shared<std::vector<float>>(outv.values.begin(), outv.values.end());
                cached.first = times;
                cached.second = values;
                const std::size_t perKey = (out.interpolation == Interpolation::CubicSpline ? 3u : 1u);
                if (outv.count != times->size() * perKey)
                    fail(sw + "/output", "holds " + std::to_string(outv.count) + " elements for " + std::to_string(times->size()) +
                                             " keys (" + s.interpolation + " needs " + std::to_string(times->size() * perKey) + ")");
                info.duration = std::max(info.duration, double(times->back()));
                if (outv.width != (path == 1 ? 4 : 3))
                    fail(sw + "/output", "has " + std::to_string(outv.width) + " components, " + ch.target_path + " needs " +
                                             std::to_string(path == 1 ? 4 : 3));
            } else {
                const std::size_t width = path == 1 ? 4 : 3;
                const std::size_t perKey = (out.interpolation == Interpolation::CubicSpline ? 3u : 1u);
                if (cached.second->size() != cached.first->size() * perKey * width)
                    fail(sw + "/output", "is used for paths of different widths");
            }
            out.times = cached.first;
            out.values = cached.second;
            channels_[a].push_back(out);
            animatedNodes_.insert(out.node);
        }
        asset_.animations.push_back(info);
    }
}

double Loader::restExtent(const std::vector<dvec3>& points) const {
    double far = 0;
    for (const dvec3& p : points) far = std::max(far, glm::length(p));
    return far;
}

std::shared_ptr<MeshData> Loader::mergeSkinned(int s, const std::vector<int>& prims) {
    auto merged = std::make_shared<MeshData>();
    merged->name = (m_.skins[static_cast<std::size_t>(s)].name.empty() ? name_ : m_.skins[static_cast<std::size_t>(s)].name) + "/skinned";
    bool normals = true, eight = false;
    std::map<int, std::size_t> textureTriangles;
    std::vector<glm::vec4> colours;
    for (int i : prims) {
        const MeshData& p = *prims_[static_cast<std::size_t>(i)].local;
        normals = normals && !p.normals.empty();
        eight = eight || !p.joints1.empty();
        if (prims_[static_cast<std::size_t>(i)].texture >= 0) textureTriangles[prims_[static_cast<std::size_t>(i)].texture] += p.triangleCount();
        if (std::find(colours.begin(), colours.end(), p.baseColor) == colours.end()) colours.push_back(p.baseColor);
    }
    int chosen = -1;
    std::size_t best = 0;
    for (const auto& [img, tris] : textureTriangles)
        if (tris > best) best = tris, chosen = img;
    if (textureTriangles.size() > 1)
        warn(ptr("/skins", static_cast<std::size_t>(s)), std::to_string(textureTriangles.size()) +
                                                             " textures on one skinned mesh: image " + std::to_string(chosen) +
                                                             " (most triangles) kept for all");
    const bool palette = chosen < 0 && colours.size() > 1;
    std::shared_ptr<Image> paletteImage;
    if (palette) {
        paletteImage = std::make_shared<Image>();
        paletteImage->name = merged->name + "/palette";
        paletteImage->width = static_cast<int>(colours.size());
        paletteImage->height = 1;
        for (const glm::vec4& c : colours)
            paletteImage->rgba.insert(paletteImage->rgba.end(), {toSrgb8(c.r), toSrgb8(c.g), toSrgb8(c.b),
                                                                 static_cast<std::uint8_t>(std::lround(std::clamp(c.a, 0.0f, 1.0f) * 255))});
        merged->baseColorTexture = paletteImage;
    }
    for (int i : prims) {
        const Prim& pr = prims_[static_cast<std::size_t>(i)];
        const MeshData& p = *pr.local;
        const auto base = static_cast<std::uint32_t>(merged->positions.size());
        merged->positions.insert(merged->positions.end(), p.positions.begin(), p.positions.end());
        if (normals) merged->normals.insert(merged->normals.end(), p.normals.begin(), p.normals.end());
        for (std::uint32_t k : p.indices) merged->indices.push_back(base + k);
        merged->joints0.insert(merged->joints0.end(), p.joints0.begin(), p.joints0.end());
        merged->weights0.insert(merged->weights0.end(), p.weights0.begin(), p.weights0.end());
        if (eight) {
            if (p.joints1.empty()) {
                merged->joints1.insert(merged->joints1.end(), p.vertexCount(), glm::u16vec4(0));
                merged->weights1.insert(merged->weights1.end(), p.vertexCount(), glm::vec4(0));
            } else {
                merged->joints1.insert(merged->joints1.end(), p.joints1.begin(), p.joints1.end());
                merged->weights1.insert(merged->weights1.end(), p.weights1.begin(), p.weights1.end());
            }
        }
        if (palette) {
            const auto c = static_cast<float>(std::find(colours.begin(), colours.end(), p.baseColor) - colours.begin());
            merged->texcoords.insert(merged->texcoords.end(), p.vertexCount(), glm::vec2((c + 0.5f) / float(colours.size()), 0.5f));
        } else if (chosen >= 0) {
            if (pr.texture == chosen) merged->texcoords.insert(merged->texcoords.end(), p.texcoords.begin(), p.texcoords.end());
            else merged->texcoords.insert(merged->texcoords.end(), p.vertexCount(), glm::vec2(0.0f));
            merged->baseColorTexture = p.baseColorTexture && pr.texture == chosen ? p.baseColorTexture : merged->baseColorTexture;
        }
    }
    if (!palette && !prims.empty()) {
        // The colour of the chosen texture's primitive, or the single colour.
        for (int i : prims)
            if (chosen < 0 || prims_[static_cast<std::size_t>(i)].texture == chosen) {
                merged->baseColor = prims_[static_cast<std::size_t>(i)].local->baseColor;
                break;
            }
    }
    if (chosen >= 0 && !merged->baseColorTexture) merged->texcoords.clear();
    return merged;
}

void Loader::buildSkin(int s) {
    const auto& joints = skinJoints_[static_cast<std::size_t>(s)];
    std::map<int, int> jointIndex;  // glTF node -> skin joint k
    for (std::size_t k = 0; k < joints.size(); ++k) jointIndex[joints[k]] = static_cast<int>(k);
    const std::string skinName = m_.skins[static_cast<std::size_t>(s)].name;
    std::string tmplName = name_;
    if (m_.skins.size() > 1) tmplName += "/" + (skinName.empty() ? "skin" + std::to_string(s) : skinName);
    ActorTemplateBuilder builder(tmplName);
    LoadedCharacter ch;
    ch.skin = s;
    ch.jointCount = static_cast<int>(joints.size());
    std::vector<SkeletonNode> nodes;
    std::set<std::string> names;
    auto unique = [&](std::string n) {
        std::string u = n;
        for (int k = 2; names.count(u); ++k) u = n + "#" + std::to_string(k);
        names.insert(u);
        return u;
    };
    std::vector<JointFold> fold(m_.nodes.size());
    std::vector<int> skeletonOfJoint(joints.size(), -1);
    // An animated node above a joint moves the joint (glTF: a joint's global transform includes
    // its ancestors'): it becomes a Skeleton node with DOFs, as a joint, instead of being folded.
    std::vector<char> aboveJoint(m_.nodes.size(), 0);
    for (int j : joints)
        for (int a = parent_[static_cast<std::size_t>(j)]; a >= 0; a = parent_[static_cast<std::size_t>(a)])
            aboveJoint[static_cast<std::size_t>(a)] = 1;
    // Rigid primitives below each glTF joint node (the nearest joint ancestor-or-self).
    std::map<int, std::vector<int>> rigidUnder;
    std::vector<int> skinned;
    for (std::size_t i = 0; i < prims_.size(); ++i) {
        const Prim& p = prims_[i];
        if (p.skin == s) {
            skinned.push_back(static_cast<int>(i));
            continue;
        }
        if (p.skin >= 0) continue;
        for (int a = p.node; a >= 0; a = parent_[static_cast<std::size_t>(a)])
            if (jointIndex.count(a)) {
                rigidUnder[a].push_back(static_cast<int>(i));
                break;
            }
    }
    for (const auto& [node, list] : rigidUnder)
        for (int i : list) rigidClaimed_.insert(i);

    // Depth-first over the whole hierarchy from the joints' common root.
    int root = joints[0];
    while (parent_[static_cast<std::size_t>(root)] >= 0) root = parent_[static_cast<std::size_t>(root)];
    struct Item {
        int node;
        int skeletonParent;
        dmat4 above;  // non-joint transforms since the skeleton parent (or the world origin)
    };
    std::vector<Item> stack{{root, -1, fileScale()}};
    std::vector<dvec3> extentPoints;
    while (!stack.empty()) {
        Item it = stack.back();
        stack.pop_back();
        const auto n = static_cast<std::size_t>(it.node);
        int skeletonHere = it.skeletonParent;
        dmat4 above = it.above * local_[n];
        const bool joint = jointIndex.count(it.node) > 0;
        if (joint || (aboveJoint[n] && animatedNodes_.count(it.node))) {
            Trs b = decompose(it.above);
            int parent = it.skeletonParent;
            if (!nearIdentity(it.above) && !b.uniform) {
                // Cannot fold a non-uniform scale into the joint's DOFs: a DOF-less node keeps it.
                const int holder = parent_[n];
                warn(ptr("/nodes", static_cast<std::size_t>(holder)),
                     std::string("non-uniform scale") + (b.exact ? "" : " with shear (approximated)") +
                         " above '" + nodeName(it.node) + "' kept as a Skeleton node without DOFs");
                SkeletonNode keep;
                keep.name = unique(nodeName(holder));
                keep.parent = parent;
                keep.restTranslation = glm::vec3(b.t);
                keep.restRotation = glm::quat(b.r);
                keep.restScale = glm::vec3(b.s);
                nodes.push_back(keep);
                ch.nodeSource.push_back(holder);
                parent = static_cast<int>(nodes.size()) - 1;
                b = Trs{};
            }
            const Trs& j = trs_[n];
            SkeletonNode sn;
            sn.name = unique(nodeName(it.node));
            sn.parent = parent;
            sn.restTranslation = glm::vec3(b.t);
            sn.restRotation = glm::quat(b.r);
            sn.restScale = glm::vec3(b.s.x);
            const dvec3 pos = b.s.x * (b.r * j.t);
            Dof position{DofKind::Position, glm::vec3(0), -INFINITY, INFINITY, {float(pos.x), float(pos.y), float(pos.z), 0}};
            Dof orientation{DofKind::Orientation, glm::vec3(0), -INFINITY, INFINITY, {float(j.r.x), float(j.r.y), float(j.r.z), float(j.r.w)}};
            Dof scale{DofKind::Scale, glm::vec3(0), -INFINITY, INFINITY, {float(j.s.x), float(j.s.y), float(j.s.z), 0}};
            sn.dofs = {position, orientation, scale};
            const int k = joint ? jointIndex[it.node] : -1;
            if (joint) sn.inverseBind = ibm_[static_cast<std::size_t>(s)][static_cast<std::size_t>(k)];
            nodes.push_back(sn);
            ch.nodeSource.push_back(it.node);
            skeletonHere = static_cast<int>(nodes.size()) - 1;
            if (joint) skeletonOfJoint[static_cast<std::size_t>(k)] = skeletonHere;
            fold[n] = JointFold{skeletonHere, b.s.x, b.r};
            above = dmat4(1.0);
            extentPoints.push_back(dvec3(world_[n][3]));
            // Rigid geometry of this joint: one DOF-less child per primitive, in the joint's frame.
            if (auto r = rigidUnder.find(it.node); r != rigidUnder.end()) {
                const dmat4 toJoint = glm::inverse(world_[n]);
                for (int pi : r->second) {
                    const Prim& p = prims_[static_cast<std::size_t>(pi)];
                    auto mesh = std::make_shared<MeshData>(*p.world);
                    for (auto& v : mesh->positions) v = glm::vec3(toJoint * glm::dvec4(dvec3(v), 1.0));
                    const glm::dmat3 nm = glm::inverseTranspose(glm::dmat3(toJoint));
                    for (auto& v : mesh->normals) {
                        const dvec3 d = nm * dvec3(v);
                        v = glm::length(d) > 0 ? glm::vec3(glm::normalize(d)) : v;
                    }
                    SkeletonNode g;
                    g.name = unique(sn.name + "/" + mesh->name);
                    g.parent = skeletonHere;
                    g.geometry.addLevel(std::numeric_limits<double>::infinity(), std::make_shared<MeshDrawable>(mesh));
                    nodes.push_back(g);
                    ch.nodeSource.push_back(p.node);
                    ch.primitives.push_back(pi);
                    for (const auto& v : p.world->positions) extentPoints.push_back(dvec3(v));
                }
            }
        }
        const auto& children = m_.nodes[n].children;
        for (auto c = children.rbegin(); c != children.rend(); ++c) stack.push_back({*c, skeletonHere, above});
    }
    for (std::size_t k = 0; k < joints.size(); ++k)
        if (skeletonOfJoint[k] < 0) fail(ptr(ptr("/skins", static_cast<std::size_t>(s)) + "/joints", k), "joint not reached from the common root");

    // The skinned mesh and the joints' internal spheres (bind-pose vertices each joint dominates).
    std::shared_ptr<MeshData> mesh;
    if (!skinned.empty()) {
        mesh = mergeSkinned(s, skinned);
        std::vector<BoundingSphere> spheres(joints.size());
        std::vector<BoundingSphere> parts(nodes.size());  // bind space, metres: what each node moves
        for (std::size_t v = 0; v < mesh->vertexCount(); ++v) {
            int bestK = mesh->joints0[v][0];
            float bestW = mesh->weights0[v][0];
            for (int c = 1; c < 8; ++c) {
                const bool second = c >= 4;
                if (second && mesh->joints1.empty()) break;
                const float w = second ? mesh->weights1[v][c - 4] : mesh->weights0[v][c];
                if (w > bestW) bestW = w, bestK = second ? mesh->joints1[v][c - 4] : mesh->joints0[v][c];
            }
            const glm::dvec4 p = glm::dmat4(ibm_[static_cast<std::size_t>(s)][static_cast<std::size_t>(bestK)]) *
                                 glm::dvec4(dvec3(mesh->positions[v]), 1.0);
            if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) spheres[static_cast<std::size_t>(bestK)].expandBy(dvec3(p));
            extentPoints.push_back(options_.scale * dvec3(mesh->positions[v]));  // bind space, scaled
            if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
                parts[static_cast<std::size_t>(skeletonOfJoint[static_cast<std::size_t>(bestK)])].expandBy(extentPoints.back());
        }
        if (options_.jointMinAngle > 0.0) deactivateSmallParts(nodes, std::move(parts), options_.jointMinAngle);
        for (std::size_t k = 0; k < joints.size(); ++k)
            nodes[static_cast<std::size_t>(skeletonOfJoint[k])].geometrySphere = spheres[k];
        for (int i : skinned) ch.primitives.push_back(i);
    }
    for (SkeletonNode& sn : nodes) {
        try {
            builder.addNode(sn);
        } catch (const std::invalid_argument& e) {
            fail(ptr("/skins", static_cast<std::size_t>(s)), e.what());
        }
    }
    Skin skin;
    skin.name = skinName.empty() ? tmplName : skinName;
    for (int k : skeletonOfJoint) skin.joints.push_back(static_cast<std::uint32_t>(k));
    const int skinIndex = builder.addSkin(skin);
    if (mesh && options_.lodLevels.empty()) {
        builder.rootGeometry().addLevel(std::numeric_limits<double>::infinity(), std::make_shared<MeshDrawable>(mesh), skinIndex);
        ch.lodErrors.push_back(0.0);
    } else if (mesh) {
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
            builder.rootGeometry().addLevel(level.maxDistance, std::make_shared<MeshDrawable>(shown), skinIndex);
            ch.lodErrors.push_back(error);
        }
    }

    // Clips: one per animation that drives one of these joints.
    std::set<std::string> clipNames;
    for (std::size_t a = 0; a < channels_.size(); ++a) {
        std::vector<ClipChannel> out;
        for (std::size_t c = 0; c < channels_[a].size(); ++c) {
            const Channel& in = channels_[a][c];
            const JointFold& f = fold[static_cast<std::size_t>(in.node)];
            if (f.skeleton < 0) continue;  // not a Skeleton node of this template
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
                    if (!(len > 1e-6)) fail(ptr("/animations", a) + "/channels/" + std::to_string(in.index), "key " + std::to_string(k / 4) + " is a zero quaternion");
                    for (int q = 0; q < 4; ++q) cc.values[k + static_cast<std::size_t>(q)] = static_cast<float>(cc.values[k + static_cast<std::size_t>(q)] / len);
                }
            out.push_back(std::move(cc));
            loadedChannels_[a].insert(in.index);
        }
        if (out.empty()) continue;
        std::string clipName = asset_.animations[a].name;
        for (int k = 2; clipNames.count(clipName); ++k) clipName = asset_.animations[a].name + "#" + std::to_string(k);
        clipNames.insert(clipName);
        try {
            builder.addClip(std::make_shared<const AnimationClip>(clipName, std::move(out)));
        } catch (const std::invalid_argument& e) {
            fail(ptr("/animations", a), e.what());
        }
        ch.clipSource.push_back(static_cast<int>(a));
    }
    const double margin = options_.sklsrootMargin >= 0 ? options_.sklsrootMargin : std::max(0.05, 0.01 * restExtent(extentPoints));
    try {
        builder.setSkeletonRootMargin(margin);
        builder.setRadiusSampleRate(options_.sklsrootSampleRate);
        ch.tmpl = builder.build();
    } catch (const std::invalid_argument& e) {
        fail(ptr("/skins", static_cast<std::size_t>(s)), e.what());
    }
    asset_.characters.push_back(std::move(ch));
}

void Loader::buildStatic() {
    std::vector<int> statics;
    for (std::size_t i = 0; i < prims_.size(); ++i)
        if (prims_[i].skin < 0 && !rigidClaimed_.count(static_cast<int>(i))) statics.push_back(static_cast<int>(i));
    if (statics.empty()) return;
    ActorTemplateBuilder builder(m_.skins.empty() ? name_ : name_ + "/static");
    LoadedCharacter ch;
    std::vector<dvec3> extent;
    std::set<std::string> names;
    for (int i : statics) {
        const Prim& p = prims_[static_cast<std::size_t>(i)];
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
    const double margin = options_.sklsrootMargin >= 0 ? options_.sklsrootMargin : std::max(0.05, 0.01 * restExtent(extent));
    try {
        builder.setSkeletonRootMargin(margin);
        builder.setRadiusSampleRate(options_.sklsrootSampleRate);
        ch.tmpl = builder.build();
    } catch (const std::invalid_argument& e) {
        fail("/meshes", e.what());
    }
    asset_.characters.push_back(std::move(ch));
}

CharacterAsset Loader::run() {
    asset_.source = doc_.file;
    checkOptions();
    readNodes();
    readScene();
    checkSkins();
    if (m_.nodes.empty() && m_.meshes.empty()) fail("/", "the file holds no node and no mesh: nothing to load");
    readPrimitives();
    readAnimations();
    for (std::size_t s = 0; s < m_.skins.size(); ++s) buildSkin(static_cast<int>(s));
    buildStatic();
    for (std::size_t a = 0; a < channels_.size(); ++a)
        asset_.animations[a].channelsLoaded = static_cast<int>(loadedChannels_[a].size());
    asset_.warnings = doc_.warnings;
    return std::move(asset_);
}

void Loader::checkOptions() const {
    if (!(std::isfinite(options_.scale) && options_.scale > 0.0))
        fail("/", "GltfLoadOptions::scale must be a positive number, got " + std::to_string(options_.scale));
    if (!(options_.jointMinAngle >= 0.0 && options_.jointMinAngle < 1.0))
        fail("/", "GltfLoadOptions::jointMinAngle must be in [0, 1) radians, got " + std::to_string(options_.jointMinAngle));
    double previous = 0.0;
    for (std::size_t i = 0; i < options_.lodLevels.size(); ++i) {
        const GltfLodLevel& l = options_.lodLevels[i];
        const std::string which = "GltfLoadOptions::lodLevels[" + std::to_string(i) + "]";
        if (!(l.maxDistance > previous)) fail("/", which + ": maxDistance must exceed the previous level's (" + std::to_string(previous) + ")");
        if (!(l.triangleShare > 0.0 && l.triangleShare <= 1.0)) fail("/", which + ": triangleShare must be in (0, 1]");
        previous = l.maxDistance;
    }
}

std::string stem(const std::string& path) {
    const std::string s = std::filesystem::path(path).stem().string();
    return s.empty() ? path : s;
}

CharacterAsset load(const std::vector<std::uint8_t>& bytes, const std::string& file, const std::string& name,
                    const std::string& baseDirectory, const GltfLoadOptions& options) {
    GltfDocument doc = parseDocument(bytes, file, baseDirectory, options);
    Loader loader(doc, options, name);
    return loader.run();
}

}  // namespace
}  // namespace gltf

CharacterAsset loadCharacter(const std::string& path, const GltfLoadOptions& options) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const auto size = fs::file_size(path, ec);
    if (ec) throw GltfError(path, "/", "cannot read the file (" + ec.message() + ")");
    if (size > options.limits.maxFileBytes)
        throw GltfError(path, "/", "the file holds " + std::to_string(size) + " bytes, more than the limit of " +
                                       std::to_string(options.limits.maxFileBytes));
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
    std::ifstream in(path, std::ios::binary);
    if (!in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size)))
        throw GltfError(path, "/", "cannot read the file");
    std::string base = options.baseDirectory;
    if (base.empty()) {
        base = fs::path(path).parent_path().string();
        if (base.empty()) base = ".";
    }
    return gltf::load(bytes, path, gltf::stem(path), base, options);
}

CharacterAsset loadCharacterFromMemory(const std::vector<std::uint8_t>& bytes, const std::string& name,
                                       const GltfLoadOptions& options) {
    return gltf::load(bytes, name, gltf::stem(name), options.baseDirectory, options);
}

}  // namespace throng
