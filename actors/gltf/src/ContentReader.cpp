// The glTF loader's reading half: the node tree, the default scene, skins, primitives and
// animations, each value checked before anything is built from it. See ContentReader.h.

#include "ContentReader.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_inverse.hpp>

#include "ImageDecoder.h"
#include "JsonPointer.h"

namespace throng::gltf {

GltfContent ContentReader::read() {
    readNodes();
    readScene();
    checkSkins();
    if (m_.nodes.empty() && m_.meshes.empty()) doc_.fail("/", "the file holds no node and no mesh: nothing to load");
    readPrimitives();
    readAnimations();
    return std::move(c_);
}

void ContentReader::readNodes() {
    const std::size_t n = m_.nodes.size();
    c_.parent.assign(n, -1);
    c_.local.assign(n, dmat4(1.0));
    c_.world.assign(n, dmat4(1.0));
    c_.trs.assign(n, Trs{});
    for (std::size_t i = 0; i < n; ++i) {
        const tinygltf::Node& node = m_.nodes[i];
        const std::string where = ptr("/nodes", i);
        for (std::size_t k = 0; k < node.children.size(); ++k) {
            const int c = node.children[k];
            if (c < 0 || static_cast<std::size_t>(c) >= n) doc_.fail(ptr(where + "/children", k), "node " + std::to_string(c) + " does not exist");
            if (static_cast<std::size_t>(c) == i) doc_.fail(ptr(where + "/children", k), "a node cannot be its own child");
            if (c_.parent[static_cast<std::size_t>(c)] >= 0)
                doc_.fail(ptr(where + "/children", k), "node " + std::to_string(c) + " already has parent " +
                                                       std::to_string(c_.parent[static_cast<std::size_t>(c)]));
            c_.parent[static_cast<std::size_t>(c)] = static_cast<int>(i);
        }
        if (node.mesh >= 0 && static_cast<std::size_t>(node.mesh) >= m_.meshes.size()) doc_.fail(where + "/mesh", "mesh " + std::to_string(node.mesh) + " does not exist");
        if (node.skin >= 0 && static_cast<std::size_t>(node.skin) >= m_.skins.size()) doc_.fail(where + "/skin", "skin " + std::to_string(node.skin) + " does not exist");
        Trs& d = c_.trs[i];
        if (!node.matrix.empty()) {
            if (node.matrix.size() != 16) doc_.fail(where + "/matrix", "must hold 16 numbers");
            dmat4 mat;
            for (int k = 0; k < 16; ++k) {
                if (!std::isfinite(node.matrix[static_cast<std::size_t>(k)])) doc_.fail(where + "/matrix", "value " + std::to_string(k) + " is not finite");
                mat[k / 4][k % 4] = node.matrix[static_cast<std::size_t>(k)];
            }
            if (mat[0][3] != 0 || mat[1][3] != 0 || mat[2][3] != 0 || mat[3][3] != 1) doc_.fail(where + "/matrix", "is not an affine transform");
            c_.local[i] = mat;
            d = decompose(mat);
            if (!d.exact) doc_.warn(where + "/matrix", "has shear, which animation would lose: decomposed approximately");
        } else {
            auto vec = [&](const std::vector<double>& v, std::size_t size, const char* key) {
                if (!v.empty() && v.size() != size) doc_.fail(where + "/" + key, "must hold " + std::to_string(size) + " numbers");
                for (std::size_t k = 0; k < v.size(); ++k)
                    if (!std::isfinite(v[k])) doc_.fail(where + "/" + key, "value " + std::to_string(k) + " is not finite");
            };
            vec(node.translation, 3, "translation");
            vec(node.rotation, 4, "rotation");
            vec(node.scale, 3, "scale");
            if (!node.translation.empty()) d.t = dvec3(node.translation[0], node.translation[1], node.translation[2]);
            if (!node.rotation.empty()) {
                const dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
                const double len = glm::length(q);
                if (!(len > 1e-6)) doc_.fail(where + "/rotation", "is a zero quaternion");
                d.r = q / len;
            }
            if (!node.scale.empty()) d.s = dvec3(node.scale[0], node.scale[1], node.scale[2]);
            d.uniform = d.s.x > 0 && d.s.x == d.s.y && d.s.x == d.s.z;
            c_.local[i] = compose(d.t, d.r, d.s);
        }
    }
    // Cycles: with one parent per node, a cycle is a loop no root reaches.
    for (std::size_t i = 0; i < n; ++i) {
        std::size_t steps = 0;
        for (int a = c_.parent[i]; a >= 0; a = c_.parent[static_cast<std::size_t>(a)])
            if (++steps > n) doc_.fail(ptr("/nodes", i), "is part of a cycle of children");
    }
    // World matrices, parents first.
    std::vector<int> stack;
    for (std::size_t i = 0; i < n; ++i)
        if (c_.parent[i] < 0) stack.push_back(static_cast<int>(i));
    while (!stack.empty()) {
        const auto i = static_cast<std::size_t>(stack.back());
        stack.pop_back();
        c_.world[i] = c_.parent[i] >= 0 ? c_.world[static_cast<std::size_t>(c_.parent[i])] * c_.local[i] : uniformScale(options_.scale) * c_.local[i];
        for (int c : m_.nodes[i].children) stack.push_back(c);
    }
}

void ContentReader::readScene() {
    const std::size_t n = m_.nodes.size();
    c_.inScene.assign(n, 0);
    std::vector<int> roots;
    if (!m_.scenes.empty()) {
        int s = m_.defaultScene;
        if (s < 0) s = 0;
        if (static_cast<std::size_t>(s) >= m_.scenes.size()) doc_.fail("/scene", "scene " + std::to_string(s) + " does not exist");
        const auto& nodes = m_.scenes[static_cast<std::size_t>(s)].nodes;
        for (std::size_t k = 0; k < nodes.size(); ++k) {
            const int r = nodes[k];
            const std::string where = ptr(ptr("/scenes", static_cast<std::size_t>(s)) + "/nodes", k);
            if (r < 0 || static_cast<std::size_t>(r) >= n) doc_.fail(where, "node " + std::to_string(r) + " does not exist");
            if (c_.parent[static_cast<std::size_t>(r)] >= 0) doc_.fail(where, "node " + std::to_string(r) + " is not a root node");
            roots.push_back(r);
        }
    } else {
        for (std::size_t i = 0; i < n; ++i)
            if (c_.parent[i] < 0) roots.push_back(static_cast<int>(i));
    }
    // Depth first, children in order.
    std::vector<int> stack(roots.rbegin(), roots.rend());
    while (!stack.empty()) {
        const int i = stack.back();
        stack.pop_back();
        if (c_.inScene[static_cast<std::size_t>(i)]) continue;
        c_.inScene[static_cast<std::size_t>(i)] = 1;
        c_.order.push_back(i);
        const auto& ch = m_.nodes[static_cast<std::size_t>(i)].children;
        for (auto it = ch.rbegin(); it != ch.rend(); ++it) stack.push_back(*it);
    }
}

void ContentReader::checkSkins() {
    const std::size_t n = m_.nodes.size();
    auto rootOf = [&](int i) {
        while (c_.parent[static_cast<std::size_t>(i)] >= 0) i = c_.parent[static_cast<std::size_t>(i)];
        return i;
    };
    auto isAncestorOrSelf = [&](int a, int i) {
        for (; i >= 0; i = c_.parent[static_cast<std::size_t>(i)])
            if (i == a) return true;
        return false;
    };
    c_.skinJoints.resize(m_.skins.size());
    c_.inverseBinds.resize(m_.skins.size());
    // Pass 1: references and formats of every skin; pass 2 reads the matrices.
    for (std::size_t s = 0; s < m_.skins.size(); ++s) {
        const tinygltf::Skin& skin = m_.skins[s];
        const std::string where = ptr("/skins", s);
        std::set<int> seen;
        for (std::size_t k = 0; k < skin.joints.size(); ++k) {
            const int j = skin.joints[k];
            if (j < 0 || static_cast<std::size_t>(j) >= n)
                doc_.fail(ptr(where + "/joints", k), "node " + std::to_string(j) + " does not exist (" + std::to_string(n) + " nodes)");
            if (!seen.insert(j).second) doc_.fail(ptr(where + "/joints", k), "node " + std::to_string(j) + " is listed twice");
        }
        if (skin.joints.size() > 65535) doc_.fail(where + "/joints", "more than 65535 joints");
        const int root = rootOf(skin.joints[0]);
        for (int j : skin.joints)
            if (rootOf(j) != root) doc_.fail(where + "/joints", "joints do not have a common root");
        if (skin.skeleton >= 0) {
            if (static_cast<std::size_t>(skin.skeleton) >= n) doc_.fail(where + "/skeleton", "node " + std::to_string(skin.skeleton) + " does not exist");
            for (int j : skin.joints)
                if (!isAncestorOrSelf(skin.skeleton, j))
                    doc_.fail(where + "/skeleton", "node " + std::to_string(skin.skeleton) + " is not a common root of the joints");
        }
        if (skin.inverseBindMatrices >= 0) {
            const auto& a = reader_.accessor(skin.inverseBindMatrices, where + "/inverseBindMatrices");
            if (a.type != TINYGLTF_TYPE_MAT4 || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
                doc_.fail(where + "/inverseBindMatrices", "accessor must be MAT4 of FLOAT");
            if (a.count < skin.joints.size())
                doc_.fail(where + "/inverseBindMatrices", "accessor holds " + std::to_string(a.count) + " matrices for " +
                                                         std::to_string(skin.joints.size()) + " joints");
        }
        c_.skinJoints[s] = skin.joints;
    }
    for (std::size_t s = 0; s < m_.skins.size(); ++s) {
        const tinygltf::Skin& skin = m_.skins[s];
        const std::string where = ptr("/skins", s) + "/inverseBindMatrices";
        c_.inverseBinds[s].assign(skin.joints.size(), glm::mat4(1.0f));
        if (skin.inverseBindMatrices < 0) continue;
        const auto& a = m_.accessors[static_cast<std::size_t>(skin.inverseBindMatrices)];
        if (a.bufferView < 0 && !a.sparse.isSparse) {
            doc_.warn(where, "accessor holds no data: identity matrices used");
            continue;
        }
        if (m_.bufferViews.size() > static_cast<std::size_t>(std::max(a.bufferView, 0)) && a.bufferView >= 0 &&
            m_.bufferViews[static_cast<std::size_t>(a.bufferView)].byteStride != 0)
            doc_.fail(where, "the buffer view of inverse bind matrices must not have a byteStride");
        const auto v = reader_.readNumbers(skin.inverseBindMatrices, where, false);
        for (std::size_t k = 0; k < skin.joints.size(); ++k) {
            const double* e = v.values.data() + k * 16;
            if (e[3] != 0 || e[7] != 0 || e[11] != 0 || e[15] != 1)
                doc_.fail(where, "matrix " + std::to_string(k) + " is not affine (last row must be 0 0 0 1)");
            for (int c = 0; c < 16; ++c) c_.inverseBinds[s][k][c / 4][c % 4] = static_cast<float>(e[c]);
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
            doc_.warn(where, "has a skin but no mesh: skin ignored for it");
            continue;
        }
        used[static_cast<std::size_t>(node.skin)] = 1;
        if (anyScene && c_.inScene[i])
            for (int j : c_.skinJoints[static_cast<std::size_t>(node.skin)])
                if (!c_.inScene[static_cast<std::size_t>(j)])
                    doc_.fail(where, "its skin " + std::to_string(node.skin) + " has joint " + std::to_string(j) +
                                    " which is not in the scene that shows this node");
        if (!nearIdentity(c_.local[i])) doc_.warn(where, "local transform of a skinned mesh node is ignored (glTF skinning)");
        bool parentTransform = false;
        for (int a = c_.parent[i]; a >= 0; a = c_.parent[static_cast<std::size_t>(a)])
            if (!nearIdentity(c_.local[static_cast<std::size_t>(a)])) parentTransform = true;
        if (parentTransform) doc_.warn(where, "transforms of its parent nodes are ignored for the skinned mesh (glTF skinning)");
    }
    for (std::size_t s = 0; s < m_.skins.size(); ++s)
        if (!used[s]) doc_.warn(ptr("/skins", s), "no mesh uses the skin: its template has joints only");
}

std::shared_ptr<const Image> ContentReader::texture(int imageIndex) {
    if (!options_.decodeImages || badImages_.count(imageIndex)) return nullptr;
    if (auto it = images_.find(imageIndex); it != images_.end()) return it->second;
    const tinygltf::Image& img = m_.images[static_cast<std::size_t>(imageIndex)];
    const std::string where = ptr("/images", static_cast<std::size_t>(imageIndex));
    if (img.image.empty()) {
        doc_.warn(where, "image data could not be read" + (img.uri.empty() ? std::string() : " ('" + img.uri + "')") + ": no texture");
        badImages_.insert(imageIndex);
        return nullptr;
    }
    std::string problem;
    const std::string name = img.uri.empty() ? (img.name.empty() ? "image" + std::to_string(imageIndex) : img.name) : img.uri;
    auto decoded = decodeImage(img.image, name, options_.limits.maxImagePixels, problem);
    if (!decoded) {
        doc_.warn(where, problem + ": no texture");
        badImages_.insert(imageIndex);
        return nullptr;
    }
    auto shared = std::make_shared<const Image>(std::move(*decoded));
    images_[imageIndex] = shared;
    return shared;
}

ReadPrimitive ContentReader::readPrimitive(int nodeIndex, int meshIndex, int p) {
    const tinygltf::Primitive& prim = m_.meshes[static_cast<std::size_t>(meshIndex)].primitives[static_cast<std::size_t>(p)];
    const std::string where = ptr(ptr("/meshes", static_cast<std::size_t>(meshIndex)) + "/primitives", static_cast<std::size_t>(p));
    const int skin = m_.nodes[static_cast<std::size_t>(nodeIndex)].skin;
    ReadPrimitive out;
    out.mesh = meshIndex, out.primitive = p, out.node = nodeIndex, out.skin = skin, out.material = prim.material;
    auto mesh = std::make_shared<MeshData>();
    const std::string& meshName = m_.meshes[static_cast<std::size_t>(meshIndex)].name;
    mesh->name = (meshName.empty() ? "mesh" + std::to_string(meshIndex) : meshName) + "#" + std::to_string(p);
    auto attr = [&](const char* key) {
        const auto it = prim.attributes.find(key);
        return it == prim.attributes.end() ? -1 : it->second;
    };
    const int position = attr("POSITION");
    if (position < 0) doc_.fail(where + "/attributes", "has no POSITION");
    const std::string at = where + "/attributes/";
    const auto pos = reader_.readNumbers(position, at + "POSITION");
    if (pos.width != 3 || reader_.accessor(position, at + "POSITION").type != TINYGLTF_TYPE_VEC3) doc_.fail(at + "POSITION", "must be VEC3");
    const std::size_t count = pos.count;
    for (std::size_t v = 0; v < count; ++v)
        mesh->positions.emplace_back(pos.values[v * 3], pos.values[v * 3 + 1], pos.values[v * 3 + 2]);
    auto sameCount = [&](const std::string& key, std::size_t c, int width, int expected) {
        if (c != count) doc_.fail(at + key, "holds " + std::to_string(c) + " elements, POSITION holds " + std::to_string(count));
        if (width != expected) doc_.fail(at + key, "has " + std::to_string(width) + " components, expected " + std::to_string(expected));
    };
    if (const int normal = attr("NORMAL"); normal >= 0) {
        const auto nv = reader_.readNumbers(normal, at + "NORMAL");
        sameCount("NORMAL", nv.count, nv.width, 3);
        for (std::size_t v = 0; v < count; ++v) mesh->normals.emplace_back(nv.values[v * 3], nv.values[v * 3 + 1], nv.values[v * 3 + 2]);
    }
    readMorphTargets(meshIndex, prim, where, *mesh);
    // Material: base colour and its texture.
    int texCoord = 0;
    if (prim.material >= 0) {
        if (static_cast<std::size_t>(prim.material) >= m_.materials.size())
            doc_.fail(where + "/material", "material " + std::to_string(prim.material) + " does not exist");
        const auto& pbr = m_.materials[static_cast<std::size_t>(prim.material)].pbrMetallicRoughness;
        const std::string mw = ptr("/materials", static_cast<std::size_t>(prim.material)) + "/pbrMetallicRoughness";
        if (pbr.baseColorFactor.size() == 4) {
            for (int c = 0; c < 4; ++c) {
                const double f = pbr.baseColorFactor[static_cast<std::size_t>(c)];
                if (!std::isfinite(f)) doc_.fail(mw + "/baseColorFactor", "value " + std::to_string(c) + " is not finite");
                mesh->baseColor[c] = static_cast<float>(f);
            }
        }
        if (pbr.baseColorTexture.index >= 0) {
            const int t = pbr.baseColorTexture.index;
            if (static_cast<std::size_t>(t) >= m_.textures.size())
                doc_.fail(mw + "/baseColorTexture/index", "texture " + std::to_string(t) + " does not exist");
            const int source = m_.textures[static_cast<std::size_t>(t)].source;
            if (source >= 0) {
                if (static_cast<std::size_t>(source) >= m_.images.size())
                    doc_.fail(ptr("/textures", static_cast<std::size_t>(t)) + "/source", "image " + std::to_string(source) + " does not exist");
                texCoord = pbr.baseColorTexture.texCoord;
                out.texture = source;
            } else {
                doc_.warn(ptr("/textures", static_cast<std::size_t>(t)), "has no source image (an extension we do not read?): no texture");
            }
        }
    }
    if (out.texture >= 0) {
        const std::string key = "TEXCOORD_" + std::to_string(texCoord);
        const int uv = attr(key.c_str());
        if (uv < 0) {
            doc_.warn(where, "its material's texture uses " + key + ", which it lacks: no texture");
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
        if (iv.width != 1) doc_.fail(where + "/indices", "accessor must be SCALAR");
        for (std::size_t k = 0; k < iv.values.size(); ++k)
            if (iv.values[k] >= count)
                doc_.fail(where + "/indices", "index " + std::to_string(k) + " is " + std::to_string(iv.values[k]) + ", beyond the " +
                                             std::to_string(count) + " vertices");
        idx = iv.values;
    } else {
        idx.resize(count);
        for (std::size_t v = 0; v < count; ++v) idx[v] = static_cast<std::uint32_t>(v);
    }
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        if (idx.size() % 3 != 0) doc_.fail(where, std::to_string(idx.size()) + " indices do not make whole triangles");
        mesh->indices = std::move(idx);
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        for (std::size_t k = 2; k < idx.size(); ++k) {
            if (mode == TINYGLTF_MODE_TRIANGLE_FAN) mesh->indices.insert(mesh->indices.end(), {idx[0], idx[k - 1], idx[k]});
            else if (k % 2 == 0) mesh->indices.insert(mesh->indices.end(), {idx[k - 2], idx[k - 1], idx[k]});
            else mesh->indices.insert(mesh->indices.end(), {idx[k - 1], idx[k - 2], idx[k]});
        }
    } else {
        doc_.warn(where + "/mode", "points and lines are not drawn: primitive skipped");
        return ReadPrimitive{};
    }
    // Skin influences: every JOINTS_n / WEIGHTS_n set, the largest eight kept.
    if (skin >= 0) {
        const std::size_t joints = c_.skinJoints[static_cast<std::size_t>(skin)].size();
        std::vector<std::vector<std::pair<float, std::uint32_t>>> infl(count);
        int sets = 0;
        for (int set = 0;; ++set) {
            const std::string jk = "JOINTS_" + std::to_string(set), wk = "WEIGHTS_" + std::to_string(set);
            const int ja = attr(jk.c_str()), wa = attr(wk.c_str());
            if (ja < 0 && wa < 0) break;
            if (ja < 0 || wa < 0) doc_.fail(at + (ja < 0 ? jk : wk), "is missing while " + (ja < 0 ? wk : jk) + " is given");
            const auto jv = reader_.readUnsigned(ja, at + jk);
            const auto wv = reader_.readNumbers(wa, at + wk);
            sameCount(jk, jv.count, jv.width, 4);
            sameCount(wk, wv.count, wv.width, 4);
            for (std::size_t v = 0; v < count; ++v)
                for (int c = 0; c < 4; ++c) {
                    const std::uint32_t j = jv.values[v * 4 + static_cast<std::size_t>(c)];
                    const double w = wv.values[v * 4 + static_cast<std::size_t>(c)];
                    if (w < 0) doc_.fail(at + wk, "vertex " + std::to_string(v) + " has a negative weight");
                    if (w == 0) continue;
                    if (j >= joints)
                        doc_.fail(at + jk, "vertex " + std::to_string(v) + " names joint " + std::to_string(j) + " but skin " +
                                          std::to_string(skin) + " has " + std::to_string(joints));
                    auto& list = infl[v];
                    auto same = std::find_if(list.begin(), list.end(), [&](const auto& e) { return e.second == j; });
                    if (same != list.end()) same->first += static_cast<float>(w);
                    else list.emplace_back(static_cast<float>(w), j);
                }
            ++sets;
        }
        if (sets == 0) doc_.fail(at.substr(0, at.size() - 1), "the node has a skin but the primitive has no JOINTS_0 / WEIGHTS_0");
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
        if (zero) doc_.warn(at + "WEIGHTS_0", std::to_string(zero) + " vertices have no weight: bound to the skin's first joint");
        if (dropped) doc_.warn(at + "JOINTS_0", std::to_string(dropped) + " vertices have more than 8 influences: the 8 largest kept");
        if (unnormalised) doc_.warn(at + "WEIGHTS_0", std::to_string(unnormalised) + " vertices have weights not summing to 1: normalised");
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
        const dmat4& mw = c_.world[static_cast<std::size_t>(nodeIndex)];
        const glm::dmat3 nm = glm::inverseTranspose(glm::dmat3(mw));
        transformMorphTargets(*w, mw);  // before the normals it reads are transformed
        for (std::size_t v = 0; v < w->positions.size(); ++v) {
            glm::vec3& p3 = w->positions[v];
            p3 = glm::vec3(mw * glm::dvec4(dvec3(p3), 1.0));
            if (!std::isfinite(p3.x) || !std::isfinite(p3.y) || !std::isfinite(p3.z))
                doc_.fail(at + "POSITION", "vertex " + std::to_string(v) + " lies beyond float range once placed by node " +
                                               std::to_string(nodeIndex) + "'s world transform");
        }
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
        doc_.fail(where, e.what());
    }
    return out;
}

const std::vector<std::string>& ContentReader::targetNames(int meshIndex) {
    auto& names = c_.targetNames[static_cast<std::size_t>(meshIndex)];
    if (!names.empty()) return names;
    const tinygltf::Mesh& mesh = m_.meshes[static_cast<std::size_t>(meshIndex)];
    const std::string where = ptr("/meshes", static_cast<std::size_t>(meshIndex));
    const std::size_t targets = mesh.primitives.empty() ? 0 : mesh.primitives[0].targets.size();
    for (std::size_t p = 1; p < mesh.primitives.size(); ++p)
        if (mesh.primitives[p].targets.size() != targets)
            doc_.fail(ptr(where + "/primitives", p) + "/targets", "has " + std::to_string(mesh.primitives[p].targets.size()) +
                                                                " morph targets, primitive 0 has " + std::to_string(targets) +
                                                                " (glTF: every primitive of a mesh has the same number)");
    if (!mesh.weights.empty() && mesh.weights.size() != targets)
        doc_.fail(where + "/weights", "holds " + std::to_string(mesh.weights.size()) + " weights for " + std::to_string(targets) +
                                          " morph targets");
    for (std::size_t k = 0; k < mesh.weights.size(); ++k)
        if (!std::isfinite(mesh.weights[k])) doc_.fail(ptr(where + "/weights", k), "is not finite");
    // Names: the de facto convention, extras.targetNames; otherwise "target<k>".
    const tinygltf::Value& given = mesh.extras.Has("targetNames") ? mesh.extras.Get("targetNames") : tinygltf::Value();
    bool named = false;
    if (given.IsArray()) {
        if (given.ArrayLen() != targets)
            doc_.warn(where + "/extras/targetNames", "holds " + std::to_string(given.ArrayLen()) + " names for " +
                                                         std::to_string(targets) + " morph targets: targets named by number");
        else named = true;
        for (std::size_t k = 0; named && k < targets; ++k)
            if (!given.Get(static_cast<int>(k)).IsString() || given.Get(static_cast<int>(k)).Get<std::string>().empty()) {
                doc_.warn(ptr(where + "/extras/targetNames", k), "is not a non-empty string: targets named by number");
                named = false;
            }
    } else if (mesh.extras.Has("targetNames")) {
        doc_.warn(where + "/extras/targetNames", "is not an array: targets named by number");
    }
    std::set<std::string> seen;
    for (std::size_t k = 0; k < targets; ++k) {
        const std::string base = named ? given.Get(static_cast<int>(k)).Get<std::string>() : "target" + std::to_string(k);
        std::string name = base;
        for (int n = 2; seen.count(name); ++n) name = base + "#" + std::to_string(n);
        if (name != base) doc_.warn(ptr(where + "/extras/targetNames", k), "repeats '" + base + "': renamed '" + name + "'");
        seen.insert(name);
        names.push_back(name);
    }
    return names;
}

void ContentReader::readMorphTargets(int meshIndex, const tinygltf::Primitive& prim, const std::string& where, MeshData& mesh) {
    if (prim.targets.empty()) return;
    const std::vector<std::string>& names = targetNames(meshIndex);
    const tinygltf::Mesh& gm = m_.meshes[static_cast<std::size_t>(meshIndex)];
    const std::size_t count = mesh.vertexCount();
    std::set<std::string> dropped;
    for (std::size_t k = 0; k < prim.targets.size(); ++k) {
        const std::string tw = ptr(where + "/targets", k) + "/";
        MorphTarget target;
        target.name = names[k];
        target.defaultWeight = gm.weights.empty() ? 0.0f : static_cast<float>(gm.weights[k]);
        // Offsets are VEC3, FLOAT or normalised integers, one per vertex of the primitive.
        auto offsets = [&](const std::string& key, std::vector<glm::vec3>& out) {
            const int a = prim.targets[k].at(key);
            const auto v = reader_.readNumbers(a, tw + key);
            if (v.width != 3 || reader_.accessor(a, tw + key).type != TINYGLTF_TYPE_VEC3) doc_.fail(tw + key, "must be VEC3");
            if (v.count != count)
                doc_.fail(tw + key, "holds " + std::to_string(v.count) + " offsets, the primitive has " + std::to_string(count) + " vertices");
            for (std::size_t i = 0; i < count; ++i) out.emplace_back(v.values[i * 3], v.values[i * 3 + 1], v.values[i * 3 + 2]);
        };
        for (const auto& [key, accessor] : prim.targets[k]) {
            if (key == "POSITION") offsets(key, target.positions);
            else if (key == "NORMAL" && !mesh.normals.empty()) offsets(key, target.normals);
            else if (key == "TANGENT") {
                std::vector<glm::vec3> checked;  // read and checked; no tangent is drawn
                offsets(key, checked);
                dropped.insert(key);
            } else dropped.insert(key);
        }
        if (target.positions.empty()) target.positions.assign(count, glm::vec3(0.0f));  // a target of normals alone
        mesh.morphTargets.push_back(std::move(target));
    }
    if (!dropped.empty()) {
        std::string keys;
        for (const std::string& k : dropped) keys += (keys.empty() ? "" : ", ") + k;
        doc_.warn(where + "/targets", "morph target offsets of " + keys + " are not used (no such attribute is drawn): ignored");
    }
}

void ContentReader::readPrimitives() {
    c_.targetNames.resize(m_.meshes.size());
    for (int n : c_.order) {
        const tinygltf::Node& node = m_.nodes[static_cast<std::size_t>(n)];
        if (node.mesh < 0) continue;
        const auto& mesh = m_.meshes[static_cast<std::size_t>(node.mesh)];
        if (mesh.primitives.empty()) doc_.warn(ptr("/meshes", static_cast<std::size_t>(node.mesh)) + "/primitives", "is empty");
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            ReadPrimitive prim = readPrimitive(n, node.mesh, static_cast<int>(p));
            if (!prim.local) continue;
            if (prim.local->indices.empty()) {
                doc_.warn(ptr(ptr("/meshes", static_cast<std::size_t>(node.mesh)) + "/primitives", p), "has no triangle: skipped");
                continue;
            }
            c_.primitives.push_back(prim);
            LoadedPrimitive lp;
            lp.mesh = prim.mesh, lp.primitive = prim.primitive, lp.node = prim.node, lp.skin = prim.skin, lp.material = prim.material;
            lp.data = prim.world ? prim.world : std::shared_ptr<const MeshData>(prim.local);
            asset_.primitives.push_back(lp);
        }
    }
}

void ContentReader::readAnimations() {
    // Joints, and the nodes above them: their transforms are part of the joints' global transforms.
    std::vector<char> drivesJoint(m_.nodes.size(), 0);
    for (const auto& joints : c_.skinJoints)
        for (int j : joints)
            for (int a = j; a >= 0 && !drivesJoint[static_cast<std::size_t>(a)]; a = c_.parent[static_cast<std::size_t>(a)])
                drivesJoint[static_cast<std::size_t>(a)] = 1;
    c_.channels.resize(m_.animations.size());
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
                doc_.fail(cw + "/sampler", "sampler " + std::to_string(ch.sampler) + " does not exist");
            if (ch.target_node < 0) {
                doc_.warn(cw + "/target", "has no node: ignored");
                continue;
            }
            if (static_cast<std::size_t>(ch.target_node) >= m_.nodes.size())
                doc_.fail(cw + "/target/node", "node " + std::to_string(ch.target_node) + " does not exist");
            int path = -1;
            if (ch.target_path == "translation") path = 0;
            else if (ch.target_path == "rotation") path = 1;
            else if (ch.target_path == "scale") path = 2;
            else if (ch.target_path == "weights") path = 3;
            else {
                doc_.fail(cw + "/target/path", "unknown path '" + ch.target_path + "'");
            }
            std::size_t targets = 0;  // weights: the node's mesh's morph targets
            if (path == 3) {
                const int meshIndex = m_.nodes[static_cast<std::size_t>(ch.target_node)].mesh;
                targets = meshIndex < 0 ? 0 : targetNames(meshIndex).size();
                if (targets == 0)
                    doc_.fail(cw + "/target", "animates the morph weights of node " + std::to_string(ch.target_node) +
                                                  ", whose mesh has no morph target");
            } else if (!drivesJoint[static_cast<std::size_t>(ch.target_node)]) {
                // Only joints and the nodes above them become Skeleton nodes; the data of such
                // channels is not even read.
                doc_.warn(cw, "animates node " + std::to_string(ch.target_node) + ", which is not a joint of any skin nor above one: ignored");
                continue;
            }
            const tinygltf::AnimationSampler& s = anim.samplers[static_cast<std::size_t>(ch.sampler)];
            const std::string sw = ptr(where + "/samplers", static_cast<std::size_t>(ch.sampler));
            ReadChannel out;
            out.node = ch.target_node;
            out.path = path;
            out.index = static_cast<int>(c);
            if (s.interpolation == "LINEAR") out.interpolation = Interpolation::Linear;
            else if (s.interpolation == "STEP") out.interpolation = Interpolation::Step;
            else if (s.interpolation == "CUBICSPLINE") out.interpolation = Interpolation::CubicSpline;
            else doc_.fail(sw + "/interpolation", "unknown interpolation '" + s.interpolation + "'");
            auto& cached = samplers[ch.sampler];
            if (!cached.first) {
                const auto in = reader_.readNumbers(s.input, sw + "/input", false);
                if (in.width != 1) doc_.fail(sw + "/input", "accessor must be SCALAR");
                auto times = std::make_shared<std::vector<float>>();
                for (std::size_t k = 0; k < in.count; ++k) {
                    const double t = in.values[k];
                    if (t < 0) doc_.fail(sw + "/input", "key " + std::to_string(k) + " has a negative time");
                    if (t > options_.limits.maxClipDuration)
                        doc_.fail(sw + "/input", "key " + std::to_string(k) + " at " + std::to_string(t) + " s exceeds the clip duration limit");
                    if (k > 0 && !(static_cast<float>(t) > times->back()))
                        doc_.fail(sw + "/input", "key times are not strictly increasing at key " + std::to_string(k));
                    times->push_back(static_cast<float>(t));
                }
                const auto outv = reader_.readNumbers(s.output, sw + "/output", false);
                auto values = std::make_shared<std::vector<float>>(outv.values.begin(), outv.values.end());
                cached.first = times;
                cached.second = values;
                const std::size_t perKey = (out.interpolation == Interpolation::CubicSpline ? 3u : 1u);
                if (path == 3) {
                    // Weights: a SCALAR per target per key (and per tangent for CUBICSPLINE).
                    if (outv.width != 1) doc_.fail(sw + "/output", "has " + std::to_string(outv.width) + " components, weights need SCALAR");
                    if (outv.count % targets != 0)
                        doc_.fail(sw + "/output", "holds " + std::to_string(outv.count) + " weights, not a multiple of the " +
                                                 std::to_string(targets) + " morph targets of node " + std::to_string(ch.target_node) + "'s mesh");
                    if (outv.count != times->size() * perKey * targets)
                        doc_.fail(sw + "/output", "holds " + std::to_string(outv.count) + " weights for " + std::to_string(times->size()) +
                                                 " keys of " + std::to_string(targets) + " morph targets (" + s.interpolation + " needs " +
                                                 std::to_string(times->size() * perKey * targets) + ")");
                } else {
                    if (outv.count != times->size() * perKey)
                        doc_.fail(sw + "/output", "holds " + std::to_string(outv.count) + " elements for " + std::to_string(times->size()) +
                                                 " keys (" + s.interpolation + " needs " + std::to_string(times->size() * perKey) + ")");
                    if (outv.width != (path == 1 ? 4 : 3))
                        doc_.fail(sw + "/output", "has " + std::to_string(outv.width) + " components, " + ch.target_path + " needs " +
                                                 std::to_string(path == 1 ? 4 : 3));
                }
                info.duration = std::max(info.duration, double(times->back()));
            } else {
                const std::size_t width = path == 1 ? 4 : path == 3 ? targets : 3;
                const std::size_t perKey = (out.interpolation == Interpolation::CubicSpline ? 3u : 1u);
                if (cached.second->size() != cached.first->size() * perKey * width)
                    doc_.fail(sw + "/output", "is used for paths of different widths");
            }
            out.targets = static_cast<int>(targets);
            out.times = cached.first;
            out.values = cached.second;
            c_.channels[a].push_back(out);
            if (path != 3) c_.animatedNodes.insert(out.node);  // weights move no node
        }
        asset_.animations.push_back(info);
    }
}

}  // namespace throng::gltf
