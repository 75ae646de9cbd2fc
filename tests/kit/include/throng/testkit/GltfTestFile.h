#pragma once
// Builds small glTF documents in tests: binary data goes into one base64 data-URI buffer, the JSON
// is written with nlohmann-json, so every test states its file in a few lines.

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace throng::testkit {

/// A glTF document under construction.
struct GltfTestFile {
    nlohmann::json doc = {{"asset", {{"version", "2.0"}}}};
    std::vector<std::uint8_t> bin;

    /// Appends raw bytes as a buffer view (4-byte aligned); returns its index.
    int view(const void* data, std::size_t bytes, int stride = 0) {
        while (bin.size() % 4) bin.push_back(0);
        nlohmann::json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}};
        if (stride) v["byteStride"] = stride;
        bin.insert(bin.end(), static_cast<const std::uint8_t*>(data), static_cast<const std::uint8_t*>(data) + bytes);
        return push("bufferViews", v);
    }
    /// Appends an accessor of `values` (components of `componentType`, element `type`).
    template <class T>
    int accessor(const std::vector<T>& values, const char* type, int componentType, int width, bool normalized = false) {
        const int v = view(values.data(), values.size() * sizeof(T));
        nlohmann::json a = {{"bufferView", v}, {"componentType", componentType}, {"count", values.size() / width}, {"type", type}};
        if (normalized) a["normalized"] = true;
        return push("accessors", a);
    }
    /// Float accessor of `type` ("SCALAR", "VEC3", ...).
    int floats(const std::vector<float>& v, const char* type) {
        const int w = std::string(type) == "SCALAR" ? 1 : std::string(type) == "VEC2" ? 2 : std::string(type) == "VEC3" ? 3
                      : std::string(type) == "VEC4" ? 4 : 16;
        return accessor(v, type, 5126, w);
    }
    /// Unsigned short accessor.
    int u16(const std::vector<std::uint16_t>& v, const char* type, int width) { return accessor(v, type, 5123, width); }
    /// Appends `value` to the top-level array `key`; returns its index.
    int push(const char* key, nlohmann::json value) {
        if (!doc.contains(key)) doc[key] = nlohmann::json::array();
        doc[key].push_back(std::move(value));
        return static_cast<int>(doc[key].size()) - 1;
    }
    /// The document as .gltf bytes.
    std::vector<std::uint8_t> bytes() const {
        nlohmann::json d = doc;
        if (!bin.empty())
            d["buffers"] = nlohmann::json::array(
                {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}});
        const std::string s = d.dump();
        return {s.begin(), s.end()};
    }
    static std::string base64(const std::vector<std::uint8_t>& in) {
        static const char* t = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        std::string out;
        for (std::size_t i = 0; i < in.size(); i += 3) {
            const std::uint32_t n = std::uint32_t(in[i]) << 16 | (i + 1 < in.size() ? std::uint32_t(in[i + 1]) << 8 : 0) |
                                    (i + 2 < in.size() ? in[i + 2] : 0);
            out += t[n >> 18 & 63];
            out += t[n >> 12 & 63];
            out += i + 1 < in.size() ? t[n >> 6 & 63] : '=';
            out += i + 2 < in.size() ? t[n & 63] : '=';
        }
        return out;
    }
};

/// A two-joint rig: joint "hip" (node 0) with child "knee" (node 1), a mesh node (2) skinned by
/// both over one quad, and an optional animation added by the test.
inline GltfTestFile twoJointRig() {
    GltfTestFile f;
    f.push("nodes", {{"name", "hip"}, {"translation", {0, 1, 0}}, {"children", nlohmann::json::array({1})}});
    f.push("nodes", {{"name", "knee"}, {"translation", {0, 0.5, 0}}});
    const int pos = f.floats({-0.1f, 0.5f, 0, 0.1f, 0.5f, 0, 0.1f, 1.5f, 0, -0.1f, 1.5f, 0}, "VEC3");
    const int joints = f.u16({0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4", 4);
    const int weights = f.floats({1, 0, 0, 0, 1, 0, 0, 0, 0.75f, 0.25f, 0, 0, 1, 0, 0, 0}, "VEC4");
    const int idx = f.u16({0, 1, 2, 0, 2, 3}, "SCALAR", 1);
    nlohmann::json prim = {{"attributes", {{"POSITION", pos}, {"JOINTS_0", joints}, {"WEIGHTS_0", weights}}}, {"indices", idx}};
    f.push("meshes", {{"primitives", nlohmann::json::array({prim})}});
    f.push("nodes", {{"name", "body"}, {"mesh", 0}, {"skin", 0}});
    const int ibm = f.floats({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1.5f, 0, 1}, "MAT4");
    f.push("skins", {{"joints", nlohmann::json::array({0, 1})}, {"inverseBindMatrices", ibm}});
    f.push("scenes", {{"nodes", nlohmann::json::array({0, 2})}});
    return f;
}

/// Adds an animation of one channel on `node`: path, interpolation, times and values of `type`.
inline void animate(GltfTestFile& f, int node, const char* path, const char* interpolation, const std::vector<float>& times,
                    const std::vector<float>& values, const char* type) {
    using J = nlohmann::json;
    const int in = f.floats(times, "SCALAR");
    const int out = f.floats(values, type);
    J sampler = {{"input", in}, {"output", out}, {"interpolation", interpolation}};
    J channel = {{"sampler", 0}, {"target", {{"node", node}, {"path", path}}}};
    f.push("animations", {{"name", "anim"}, {"samplers", J::array({sampler})}, {"channels", J::array({channel})}});
}

}  // namespace throng::testkit
