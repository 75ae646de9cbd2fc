#include "GltfDocument.h"

#include <cstring>
#include <string_view>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "throng/gltf/GltfError.h"

namespace throng::gltf {
namespace {

std::uint32_t readU32(const std::uint8_t* p) {
    return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}

// Deepest nesting of arrays and objects in JSON text, counted without parsing so that a hostile
// document cannot overflow the parser's stack (strings are skipped, escapes honoured).
int jsonDepth(const char* text, std::size_t size) {
    int depth = 0, deepest = 0;
    bool inString = false;
    for (std::size_t i = 0; i < size; ++i) {
        const char c = text[i];
        if (inString) {
            if (c == '\\') ++i;
            else if (c == '"') inString = false;
        } else if (c == '"') {
            inString = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
        } else if (c == ']' || c == '}') {
            --depth;
        }
    }
    return deepest;
}

// What our file callbacks need: the limits and whether files may be read at all.
struct FileContext {
    const GltfLoadOptions* options = nullptr;
    std::string baseDirectory;
};

bool fileExists(const std::string& path, void* user) {
    const auto* ctx = static_cast<const FileContext*>(user);
    if (!ctx->options->allowExternalFiles || ctx->baseDirectory.empty()) return false;
    std::error_code ec;
    return std::filesystem::is_regular_file(path, ec);
}

std::string expandPath(const std::string& path, void*) { return path; }  // never expand: no shell semantics

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    const auto* ctx = static_cast<const FileContext*>(user);
    if (!ctx->options->allowExternalFiles || ctx->baseDirectory.empty()) {
        if (err) *err += "external file '" + path + "' refused (external files are not allowed)\n";
        return false;
    }
    namespace fs = std::filesystem;
    std::error_code ec;
    // Relative URIs only, and they must stay inside the base directory.
    const fs::path base = fs::weakly_canonical(ctx->baseDirectory, ec);
    const fs::path full = fs::weakly_canonical(path, ec);
    const auto rel = full.lexically_relative(base);
    if (ec || rel.empty() || *rel.begin() == "..") {
        if (err) *err += "external file '" + path + "' lies outside the base directory\n";
        return false;
    }
    const auto size = fs::file_size(full, ec);
    if (ec || size > ctx->options->limits.maxFileBytes) {
        if (err) *err += "external file '" + path + "' is missing or larger than the file limit\n";
        return false;
    }
    std::ifstream in(full, std::ios::binary);
    out->resize(size);
    if (!in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size))) {
        if (err) *err += "cannot read external file '" + path + "'\n";
        return false;
    }
    return true;
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "the loader never writes files\n";
    return false;
}

// Image callback: keeps the encoded bytes (decoded later, only for textures a primitive uses, with
// our own decoders and limits). Checks the buffer view itself: tinygltf does not.
struct ImageContext {
    const tinygltf::Model* model = nullptr;
    std::string where;  // set when a view is out of range
};

bool keepEncodedImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                      const unsigned char* bytes, int size, void* user) {
    auto* ctx = static_cast<ImageContext*>(user);
    if (image->bufferView >= 0) {
        const auto& views = ctx->model->bufferViews;
        const auto v = static_cast<std::size_t>(image->bufferView);
        const auto b = static_cast<std::size_t>(views[v].buffer);  // both checked by tinygltf just before
        const std::uint64_t end = std::uint64_t(views[v].byteOffset) + views[v].byteLength;
        if (end > ctx->model->buffers[b].data.size()) {
            ctx->where = "/bufferViews/" + std::to_string(v);
            if (err) *err += "buffer view of image " + std::to_string(index) + " lies outside its buffer\n";
            return false;
        }
    }
    if (size < 0) return false;
    image->image.assign(bytes, bytes + size);
    image->width = image->height = 0;
    image->component = 0;  // marks "still encoded"
    return true;
}

// Checks tinygltf trusts or reports without a location, on the raw JSON.
void precheck(const nlohmann::json& doc, const std::string& file, bool binary) {
    if (!doc.is_object()) throw GltfError(file, "/", "the document is not a JSON object");
    auto array = [&](const char* key) -> const nlohmann::json* {
        const auto it = doc.find(key);
        if (it == doc.end()) return nullptr;
        if (!it->is_array()) throw GltfError(file, std::string("/") + key, "is not an array");
        return &*it;
    };
    if (const auto* buffers = array("buffers"))
        for (std::size_t i = 0; i < buffers->size(); ++i) {
            const auto& b = (*buffers)[i];
            const std::string where = "/buffers/" + std::to_string(i);
            if (!b.is_object()) throw GltfError(file, where, "is not an object");
            if (!b.contains("byteLength") || !b["byteLength"].is_number_integer() || b["byteLength"].get<std::int64_t>() < 1)
                throw GltfError(file, where, "byteLength is missing or not a positive integer");
            if (!b.contains("uri") && !(binary && i == 0))
                throw GltfError(file, where, "has no uri and no data (only the first buffer of a .glb uses the binary chunk)");
        }
    if (const auto* skins = array("skins"))
        for (std::size_t i = 0; i < skins->size(); ++i) {
            const auto& s = (*skins)[i];
            const std::string where = "/skins/" + std::to_string(i);
            if (!s.is_object()) throw GltfError(file, where, "is not an object");
            if (!s.contains("joints")) throw GltfError(file, where, "property 'joints' is missing");
            const auto& j = s["joints"];
            if (!j.is_array()) throw GltfError(file, where + "/joints", "is not an array");
            if (j.empty()) throw GltfError(file, where + "/joints", "is empty (a skin needs at least one joint)");
            for (std::size_t k = 0; k < j.size(); ++k)
                if (!j[k].is_number_integer() || j[k].get<std::int64_t>() < 0 || j[k].get<std::int64_t>() > INT32_MAX)
                    throw GltfError(file, where + "/joints/" + std::to_string(k), "is not a node index");
        }
    // Primitive references: tinygltf would reject some without saying where.
    const auto accessors = doc.contains("accessors") && doc["accessors"].is_array() ? doc["accessors"].size() : 0;
    if (const auto* meshes = array("meshes"))
        for (std::size_t i = 0; i < meshes->size(); ++i) {
            const auto& m = (*meshes)[i];
            if (!m.is_object() || !m.contains("primitives") || !m["primitives"].is_array()) continue;
            for (std::size_t p = 0; p < m["primitives"].size(); ++p) {
                const auto& prim = m["primitives"][p];
                const std::string where = "/meshes/" + std::to_string(i) + "/primitives/" + std::to_string(p);
                auto check = [&](const nlohmann::json& v, const std::string& at) {
                    if (!v.is_number_integer() || v.get<std::int64_t>() < 0 || static_cast<std::size_t>(v.get<std::int64_t>()) >= accessors)
                        throw GltfError(file, at, "accessor " + v.dump() + " does not exist (" + std::to_string(accessors) + " accessors)");
                };
                if (!prim.is_object()) continue;
                if (prim.contains("indices")) check(prim["indices"], where + "/indices");
                if (prim.contains("attributes") && prim["attributes"].is_object())
                    for (const auto& [key, value] : prim["attributes"].items()) check(value, where + "/attributes/" + key);
            }
        }
    for (const char* key : {"nodes", "meshes", "accessors", "bufferViews", "animations", "materials", "textures",
                            "images", "scenes", "samplers"})
        array(key);
}

}  // namespace

GltfDocument parseDocument(const std::vector<std::uint8_t>& bytes, const std::string& file,
                           const std::string& baseDirectory, const GltfLoadOptions& options) {
    GltfDocument doc;
    doc.file = file;
    if (bytes.size() > options.limits.maxFileBytes)
        throw GltfError(file, "/", "the file holds " + std::to_string(bytes.size()) + " bytes, more than the limit of " +
                                       std::to_string(options.limits.maxFileBytes));
    if (bytes.empty()) throw GltfError(file, "/", "the file is empty (0 bytes)");
    // Find the JSON text (GLB: check the container before tinygltf reads it).
    const char* json = reinterpret_cast<const char*>(bytes.data());
    std::size_t jsonSize = bytes.size();
    if (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0) {
        doc.binary = true;
        if (bytes.size() < 20) throw GltfError(file, "/", "the GLB header is truncated");
        if (readU32(&bytes[4]) != 2) throw GltfError(file, "/", "GLB version " + std::to_string(readU32(&bytes[4])) + " is not 2");
        const std::uint64_t length = readU32(&bytes[8]);
        if (length > bytes.size() || length < 20) throw GltfError(file, "/", "the GLB length field does not match the file size");
        const std::uint64_t chunk = readU32(&bytes[12]);
        if (readU32(&bytes[16]) != 0x4E4F534Au) throw GltfError(file, "/", "the first GLB chunk is not JSON");
        if (20 + chunk > length || chunk == 0) throw GltfError(file, "/", "the GLB JSON chunk runs past the end of the file");
        json += 20;
        jsonSize = static_cast<std::size_t>(chunk);
        std::uint64_t next = 20 + ((chunk + 3) & ~std::uint64_t(3));
        if (next + 8 <= length) {
            const std::uint64_t bin = readU32(&bytes[next]);
            if (next + 8 + bin > length) throw GltfError(file, "/", "the GLB binary chunk runs past the end of the file");
        }
    }
    const int depth = jsonDepth(json, jsonSize);
    if (depth > options.limits.maxJsonDepth)
        throw GltfError(file, "/", "JSON nesting depth " + std::to_string(depth) + " exceeds the limit of " +
                                       std::to_string(options.limits.maxJsonDepth));
    const auto parsed = nlohmann::json::parse(json, json + jsonSize, nullptr, false);
    if (parsed.is_discarded()) {
        // Say "not a glTF file" of what is neither a GLB nor a JSON object (text, an image, a .glb renamed).
        const std::string_view text(json, jsonSize);
        const std::size_t first = text.find_first_not_of(" \t\r\n\xEF\xBB\xBF");
        if (!doc.binary && (first == std::string_view::npos || text[first] != '{'))
            throw GltfError(file, "/", "is not a glTF file: neither a GLB (it would start with 'glTF') nor a JSON object");
        throw GltfError(file, "/", "the JSON is malformed");
    }
    precheck(parsed, file, doc.binary);

    FileContext files{&options, baseDirectory};
    ImageContext images{&doc.model, {}};
    tinygltf::TinyGLTF loader;
    loader.SetFsCallbacks({&fileExists, &expandPath, &readWholeFile, &writeWholeFile, &files});
    loader.SetImageLoader(&keepEncodedImage, &images);
    std::string err, warn;
    const std::string base = baseDirectory;
    bool ok = false;
    if (doc.binary)
        ok = loader.LoadBinaryFromMemory(&doc.model, &err, &warn, bytes.data(), static_cast<unsigned>(bytes.size()), base);
    else
        ok = loader.LoadASCIIFromString(&doc.model, &err, &warn, json, static_cast<unsigned>(jsonSize), base);
    auto oneLine = [](std::string s) {
        while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
        for (char& c : s)
            if (c == '\n' || c == '\r') c = ';';
        return s;
    };
    if (!ok) throw GltfError(file, images.where.empty() ? "/" : images.where, oneLine(err.empty() ? "tinygltf cannot parse it" : err));
    if (!warn.empty()) doc.warnings.push_back("/: " + oneLine(warn));

    // Buffer views must lie inside their buffers: every later read relies on it.
    const auto& m = doc.model;
    for (std::size_t i = 0; i < m.bufferViews.size(); ++i) {
        const auto& v = m.bufferViews[i];
        const std::string where = "/bufferViews/" + std::to_string(i);
        if (v.buffer < 0 || static_cast<std::size_t>(v.buffer) >= m.buffers.size())
            throw GltfError(file, where + "/buffer", "buffer " + std::to_string(v.buffer) + " does not exist");
        const std::uint64_t end = std::uint64_t(v.byteOffset) + v.byteLength;
        if (v.byteLength == 0 || end > m.buffers[static_cast<std::size_t>(v.buffer)].data.size())
            throw GltfError(file, where, "bytes [" + std::to_string(v.byteOffset) + ", " + std::to_string(end) +
                                             ") do not lie inside buffer " + std::to_string(v.buffer) + " of " +
                                             std::to_string(m.buffers[static_cast<std::size_t>(v.buffer)].data.size()) + " bytes");
        if (v.byteStride != 0 && (v.byteStride < 4 || v.byteStride > 252))
            throw GltfError(file, where + "/byteStride", "must lie in [4, 252], got " + std::to_string(v.byteStride));
    }
    return doc;
}

void GltfDocument::fail(const std::string& where, const std::string& problem) const { throw GltfError(file, where, problem); }

}  // namespace throng::gltf
