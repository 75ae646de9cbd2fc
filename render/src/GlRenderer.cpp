#include "throng/render/GlRenderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <span>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include <glad/gl.h>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include "DrawPlan.h"
#include "GlMesh.h"
#include "Shaders.h"
#include "throng/render/CpuSkinning.h"
#include "throng/render/GlContext.h"
#include "throng/render/ShaderProgram.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/DrawList.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/Stopwatch.h"

namespace throng {
namespace {

constexpr std::uint32_t kNone = 0xffffffffu;

using detail::InstanceData;
static_assert(GlRenderer::kKeyPoseVertexBytes == detail::kKeyPoseVertexBytes, "one key-pose vertex layout");

// One key-pose cache on the GPU: the rows of one (mesh, KeyPoseSource) pair, rowCount() x the mesh's
// vertex count texels of kKeyPoseVertexBytes, read by the key-pose vertex shader as a texture
// buffer. The renderer's own record of what each row holds decides what is skinned: a row is
// filled only when the pose (and skin) an item wants there is not the one it holds.
struct KeyPoseGpu {
    const KeyPoseSource* source = nullptr;  // known by address and serial (GlRenderer::releaseKeyPoses)
    std::uint64_t serial = 0;               // the source's serial: a new source at a freed one's address differs
    std::uint32_t rows = 0, poses = 0;      // the source's rowCount() and poseCount() as last seen
    GLuint buffer = 0, texture = 0;         // made on the first fill
    std::size_t bytes = 0;                  // of `buffer`
    std::vector<std::uint32_t> heldPose, heldSkin;  // per row: what it holds (kNone: nothing yet)
    // This draw()'s wants, per row (valid where wantStamp is the draw's stamp): the pose, its skin
    // and the first item that wanted it (named in a conflict).
    std::vector<std::uint32_t> wantPose, wantSkin, wantItem;
    std::vector<std::uint64_t> wantStamp;
    std::uint64_t stamp = 0;  // draw() call that set `order`
    std::uint32_t order = 0;  // first appearance among this draw's caches (fills go in that order)
    detail::BatchSlots batches;  // this draw's groups: [interpolative * 2 + mirrored]
};

struct MeshEntry {
    std::weak_ptr<const MeshData> source;  // to notice when the mesh is gone (and its address reused)
    detail::GlMesh gpu;
    GLuint cpuVao = 0;    // CPU-skinned drawing: positions and normals from the stream buffer
    GLuint texture = 0;   // owned by the texture cache
    glm::vec4 baseColor{1.0f};
    detail::BatchSlots batches;  // this draw's groups: [skinned * 2 + mirrored]
    std::vector<std::unique_ptr<KeyPoseGpu>> keyPoses;       // its key-pose caches, one per source
};

struct TextureEntry {
    std::weak_ptr<const Image> source;
    GLuint name = 0;
};

enum class Path : std::uint8_t { Rigid, GpuSkinned, CpuSkinned, KeyPose, KeyPoseBlend };

// Items drawn with one mesh and one path: one instanced draw call (CPU-skinned: one item each).
struct Group {
    MeshEntry* mesh = nullptr;
    Path path = Path::Rigid;
    bool mirrored = false;            // negative determinant: triangles wind the other way on screen
    std::uint32_t count = 0;          // items
    std::uint32_t first = 0;          // first slot in the instance buffer
    std::uint32_t cpuVertexBase = 0;  // CPU-skinned: first vertex in the stream buffer
    std::int32_t band = 0;            // front-to-back: distance band of its items (see distanceBand)
    KeyPoseGpu* keyPose = nullptr;    // key-pose paths: the cache its items read
};

// A key-pose cache row to skin this draw.
struct KeyPoseFill {
    KeyPoseGpu* cache = nullptr;
    MeshEntry* mesh = nullptr;
    std::uint32_t row = 0, pose = 0, skin = 0;
    const glm::mat4* palette = nullptr;  // the source's, at least the mesh's requiredPalette long
    std::uint32_t paletteBase = 0;       // where it goes in the palette buffer
};

struct ProgramState {
    std::unique_ptr<ShaderProgram> program;
    GLint baseColor = -1, hasTexture = -1, hasNormals = -1, viewRotation = -1, projection = -1, flatTint = -1, regionIds = -1;
    GLint lightDirection = -1, lightColor = -1, skyColor = -1, groundColor = -1, morphVertices = -1;
    std::uint64_t frameStamp = 0;  // frame whose camera and lights are loaded
};

const void* byteOffset(std::size_t bytes) { return reinterpret_cast<const void*>(bytes); }

std::string itemName(std::size_t index, const Drawable& drawable) {
    return "item " + std::to_string(index) + " (drawable '" + drawable.name() + "')";
}

void checkPositive(int width, int height, const char* where) {
    if (width <= 0) throw std::invalid_argument(std::string(where) + ": width " + std::to_string(width) + " must be positive");
    if (height <= 0) throw std::invalid_argument(std::string(where) + ": height " + std::to_string(height) + " must be positive");
}

void checkOptions(const RendererOptions& o, const char* where) {
    if (o.width < 0 || o.height < 0)
        throw std::invalid_argument(std::string(where) + ": viewport size " + std::to_string(o.width) + " x " +
                                    std::to_string(o.height) + " must not be negative (0 keeps the context's size)");
}

}  // namespace

struct GlRenderer::Impl {
    std::shared_ptr<GlContext> context;  // first member: destroyed last
    const GladGLContext& gl;
    RendererOptions options;
    RenderStatistics stats;
    Image lastFrame;
    ProgramState programs[3];  // 0, 4 and 8 influences
    ProgramState morphPrograms[3];  // the same with morph targets, built when a mesh first has them
    ProgramState constantFaces;  // rigid triangles of one colour, shaded per vertex
    ProgramState flatLight;      // rigid triangles of one normal, lit per vertex
    ProgramState keyPosePrograms[2];  // key-pose items: one row, two rows blended
    std::unique_ptr<ShaderProgram> fillPrograms[2];  // key-pose fills, 4 and 8 influences
    GLint fillBase[2] = {-1, -1}, fillStride[2] = {-1, -1};
    std::size_t keyPoseBytes = 0;     // GPU bytes of every key-pose cache
    GLuint instanceBuffer = 0, paletteBuffer = 0, paletteTexture = 0, streamBuffer = 0, whiteTexture = 0;
    GLuint morphWeightBuffer = 0, morphWeightTexture = 0;  // this draw's (target, weight) pairs, made on first use
    std::size_t instanceCapacity = 0, paletteCapacity = 0, streamCapacity = 0, morphWeightCapacity = 0;
    GLuint fragmentQuery = 0;  // GL_SAMPLES_PASSED, made on the first draw that counts fragments
    GLint maxTextureBufferTexels = 0;
    std::unordered_map<const MeshData*, std::unique_ptr<MeshEntry>> meshes;
    std::unordered_map<const Image*, TextureEntry> textures;

    bool inFrame = false;
    std::uint64_t frameStamp = 0, drawStamp = 0;
    glm::mat4 viewRotation{1.0f}, projection{1.0f};
    Vec3 eye{0.0};

    // Scratch reused by every draw(): no allocation once the crowd's size has been seen.
    std::vector<const DrawItem*> items;                     // the list's items, indexable
    std::vector<std::uint32_t> itemGroup;
    detail::DrawOrder drawOrder;                            // items in drawing order, and their distance bands
    detail::BatchPlanner planner;                           // which items share an instanced draw
    std::vector<Group> groups;
    std::vector<InstanceData> instances;
    std::vector<glm::mat4> palette;
    std::vector<glm::vec3> cpuPositions, cpuNormals;
    std::vector<glm::vec2> morphWeights;  // this draw's (target, weight) pairs, item after item
    std::vector<KeyPoseFill> fills;   // rows to skin this draw
    std::uint32_t keyPoseCaches = 0;  // caches met this draw
    const MeshData* lastMesh = nullptr;  // shortcut for runs of clones sharing a mesh
    MeshEntry* lastEntry = nullptr;

    explicit Impl(std::shared_ptr<GlContext> c) : context(std::move(c)), gl(context->gl()) {}

    ProgramState& programFor(int influences) { return programs[influences == 0 ? 0 : influences == 4 ? 1 : 2]; }

    // Builds one program and finds its uniforms (absent ones read -1 and are ignored by GL).
    void buildProgram(ProgramState& p, const std::string& name, const std::string& vertex, const std::string& fragment) {
        p.program = std::make_unique<ShaderProgram>(*context, "GlRenderer shader (" + name + ")", vertex, fragment);
        const ShaderProgram& s = *p.program;
        p.baseColor = s.uniformLocation("uBaseColor");
        p.hasTexture = s.uniformLocation("uHasTexture");
        p.hasNormals = s.uniformLocation("uHasNormals");
        p.flatTint = s.uniformLocation("uFlatTint");
        p.regionIds = s.uniformLocation("uRegionIds");
        p.viewRotation = s.uniformLocation("uViewRotation");
        p.projection = s.uniformLocation("uProjection");
        p.lightDirection = s.uniformLocation("uLightDirection");
        p.lightColor = s.uniformLocation("uLightColor");
        p.skyColor = s.uniformLocation("uSkyColor");
        p.groundColor = s.uniformLocation("uGroundColor");
        p.morphVertices = s.uniformLocation("uMorphVertices");
        gl.UseProgram(s.id());
        gl.Uniform1i(s.uniformLocation("uTexture"), detail::kBaseColorUnit);
        gl.Uniform1i(s.uniformLocation("uPalette"), detail::kPaletteUnit);
        gl.Uniform1i(s.uniformLocation("uKeyPoses"), detail::kKeyPoseUnit);
        gl.Uniform1i(s.uniformLocation("uMorphOffsets"), detail::kMorphOffsetUnit);
        gl.Uniform1i(s.uniformLocation("uMorphWeights"), detail::kMorphWeightUnit);
    }

    // The program drawing meshes with morph targets and `influences` joint influences.
    ProgramState& morphProgramFor(int influences) {
        ProgramState& p = morphPrograms[influences == 0 ? 0 : influences == 4 ? 1 : 2];
        if (!p.program)
            buildProgram(p, std::to_string(influences) + " joint influences, morph targets",
                         detail::vertexShaderSource(influences, false, true), detail::fragmentShaderSource());
        return p;
    }

    GLuint textureFor(const std::shared_ptr<const Image>& image) {
        if (!image) return 0;
        auto it = textures.find(image.get());
        if (it != textures.end() && it->second.source.expired()) {  // a new image at a freed one's address
            gl.DeleteTextures(1, &it->second.name);
            textures.erase(it);
            it = textures.end();
        }
        if (it != textures.end()) return it->second.name;
        if (!image->valid())
            throw std::invalid_argument("GlRenderer: texture '" + image->name + "' is not a valid RGBA8 image");
        TextureEntry entry{image, 0};
        gl.GenTextures(1, &entry.name);
        gl.ActiveTexture(GL_TEXTURE0 + detail::kBaseColorUnit);
        gl.BindTexture(GL_TEXTURE_2D, entry.name);
        gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
        // Rows go up top row first, so texture coordinate v = 0 is the image's top, as in glTF.
        // Base colour is sRGB-encoded: the sampler returns linear values.
        gl.TexImage2D(GL_TEXTURE_2D, 0, GL_SRGB8_ALPHA8, image->width, image->height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                      image->rgba.data());
        gl.GenerateMipmap(GL_TEXTURE_2D);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
        ++stats.textureUploads;
        textures.emplace(image.get(), entry);
        return entry.name;
    }

    void destroyKeyPose(KeyPoseGpu& k) {
        if (k.buffer) gl.DeleteBuffers(1, &k.buffer);
        if (k.texture) gl.DeleteTextures(1, &k.texture);
        k.buffer = k.texture = 0;
        keyPoseBytes -= k.bytes;
        k.bytes = 0;
    }

    void destroyEntry(MeshEntry& e) {
        detail::destroyMesh(gl, e.gpu);
        if (e.cpuVao) gl.DeleteVertexArrays(1, &e.cpuVao);
        e.cpuVao = 0;
        for (auto& k : e.keyPoses) destroyKeyPose(*k);
        e.keyPoses.clear();
    }

    // Instance attributes come from the shared instance buffer; their offsets are set per draw.
    void enableInstanceAttributes() {
        for (unsigned c = 0; c < 4; ++c) {
            gl.EnableVertexAttribArray(detail::kModel + c);
            gl.VertexAttribDivisor(detail::kModel + c, 1);
        }
        gl.EnableVertexAttribArray(detail::kTint);
        gl.VertexAttribDivisor(detail::kTint, 1);
        gl.EnableVertexAttribArray(detail::kPalette);
        gl.VertexAttribDivisor(detail::kPalette, 1);
        gl.EnableVertexAttribArray(detail::kLook);
        gl.VertexAttribDivisor(detail::kLook, 1);
    }

    MeshEntry& entryFor(const std::shared_ptr<const MeshData>& mesh) {
        const MeshData* key = mesh.get();
        if (key == lastMesh) return *lastEntry;
        auto it = meshes.find(key);
        if (it != meshes.end() && it->second->source.expired()) {  // a new mesh at a freed one's address
            destroyEntry(*it->second);
            meshes.erase(it);
            it = meshes.end();
        }
        if (it == meshes.end()) {
            auto entry = std::make_unique<MeshEntry>();
            entry->source = mesh;
            entry->texture = textureFor(mesh->baseColorTexture);
            entry->baseColor = mesh->baseColor;
            if (mesh->morphTargets.size() * mesh->vertexCount() * detail::kMorphTexelsPerVertex > static_cast<std::size_t>(maxTextureBufferTexels))
                throw std::runtime_error("GlRenderer: mesh '" + mesh->name + "': its " + std::to_string(mesh->morphTargets.size()) +
                                         " morph targets of " + std::to_string(mesh->vertexCount()) +
                                         " vertices need more texels than this GL's texture buffer limit of " +
                                         std::to_string(maxTextureBufferTexels));
            entry->gpu = detail::uploadMesh(gl, *mesh);
            gl.BindVertexArray(entry->gpu.vao);
            enableInstanceAttributes();
            gl.BindVertexArray(0);
            ++stats.meshUploads;
            it = meshes.emplace(key, std::move(entry)).first;
        }
        lastMesh = key;
        lastEntry = it->second.get();
        return *lastEntry;
    }

    GLuint cpuVaoFor(MeshEntry& e) {
        if (e.cpuVao) return e.cpuVao;
        gl.GenVertexArrays(1, &e.cpuVao);
        gl.BindVertexArray(e.cpuVao);
        gl.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, e.gpu.ibo);
        gl.EnableVertexAttribArray(detail::kPosition);
        if (e.gpu.hasNormals) gl.EnableVertexAttribArray(detail::kNormal);
        if (e.gpu.hasTexcoords) {
            gl.BindBuffer(GL_ARRAY_BUFFER, e.gpu.vbo);
            gl.EnableVertexAttribArray(detail::kTexcoord);
            gl.VertexAttribPointer(detail::kTexcoord, 2, GL_FLOAT, GL_FALSE, 0, byteOffset(e.gpu.texcoordOffset));
        }
        if (e.gpu.hasRegions) {
            gl.BindBuffer(GL_ARRAY_BUFFER, e.gpu.vbo);
            detail::enableRegions(gl, e.gpu);
        }
        enableInstanceAttributes();
        return e.cpuVao;
    }

    void pointInstanceAttributes(std::uint32_t slot) {
        constexpr GLsizei stride = sizeof(InstanceData);
        const std::size_t base = static_cast<std::size_t>(slot) * stride;
        for (unsigned c = 0; c < 4; ++c)
            gl.VertexAttribPointer(detail::kModel + c, 4, GL_FLOAT, GL_FALSE, stride, byteOffset(base + 16 * c));
        gl.VertexAttribPointer(detail::kTint, 4, GL_FLOAT, GL_FALSE, stride, byteOffset(base + offsetof(InstanceData, tint)));
        gl.VertexAttribIPointer(detail::kPalette, 3, GL_INT, stride, byteOffset(base + offsetof(InstanceData, paletteBase)));
        gl.VertexAttribIPointer(detail::kLook, 4, GL_UNSIGNED_INT, stride, byteOffset(base + offsetof(InstanceData, look)));
    }

    // The non-zero morph weights of item `i` (with mesh `e`) once clamped; throws
    // std::invalid_argument naming the item if one is not finite.
    std::uint32_t morphWeightsOf(std::uint32_t i, const DrawItem& item, const MeshEntry& e) const {
        if (!item.morphWeights || e.gpu.morphTargets == 0) return 0;
        std::uint32_t n = 0;
        for (std::uint32_t k = 0; k < e.gpu.morphTargets; ++k) {
            const float w = item.morphWeights[k];
            if (!std::isfinite(w))
                throw std::invalid_argument("GlRenderer::draw: " + itemName(i, *item.drawable) + ": morph weight " +
                                            std::to_string(k) + " is not finite");
            n += w != 0.0f;
        }
        return n;
    }

    // Key-pose item `i` (in drawing order, with mesh `e`): checks it, finds (or makes the record
    // of) its cache, records the rows it wants this draw and schedules a fill for each row whose
    // record differs. Throws std::invalid_argument naming the item; a fill is only scheduled, so
    // nothing changes on the GPU or in the records before every item has been checked.
    KeyPoseGpu& wantKeyPoses(std::uint32_t i, const DrawItem& item, MeshEntry& e) {
        const KeyPoseRef& k = item.keyPose;
        const auto fail = [&](const std::string& what) {
            throw std::invalid_argument("GlRenderer::draw: " + itemName(i, *item.drawable) + ": " + what);
        };
        if (!k.source) fail("a key-pose item without a source");
        if (e.gpu.influences == 0)
            fail("a key-pose item whose mesh '" + static_cast<const MeshDrawable*>(item.drawable)->mesh().name +
                 "' has no skin (key-poses are skinned into the cache)");
        if (!(k.blend >= 0.0f && k.blend <= 1.0f))
            fail("key-pose blend " + std::to_string(k.blend) + " is not in [0, 1]");
        const std::uint32_t rows = k.source->rowCount(), poses = k.source->poseCount();
        KeyPoseGpu* cache = nullptr;
        for (auto& c : e.keyPoses)
            if (c->source == k.source) cache = c.get();
        if (!cache && !e.keyPoses.empty() && !e.keyPoses.back()->source) cache = e.keyPoses.back().get();  // left by a failed check
        if (!cache) cache = e.keyPoses.emplace_back(std::make_unique<KeyPoseGpu>()).get();
        KeyPoseGpu& c = *cache;
        if (c.source != k.source || c.serial != k.source->serial() || c.rows != rows || c.poses != poses) {  // new, or changed
            if (static_cast<std::uint64_t>(rows) * e.gpu.vertexCount > static_cast<std::uint64_t>(maxTextureBufferTexels))
                throw std::runtime_error("GlRenderer::draw: " + itemName(i, *item.drawable) + ": a key-pose cache of " +
                                         std::to_string(rows) + " rows of " + std::to_string(e.gpu.vertexCount) +
                                         " vertices needs more texels than this GL's texture buffer limit of " +
                                         std::to_string(maxTextureBufferTexels));
            c.source = k.source;
            c.serial = k.source->serial();
            c.rows = rows;
            c.poses = poses;
            c.heldPose.assign(rows, kNone);
            c.heldSkin.assign(rows, kNone);
            c.wantPose.assign(rows, kNone);
            c.wantSkin.assign(rows, kNone);
            c.wantItem.assign(rows, kNone);
            c.wantStamp.assign(rows, 0);
        }
        if (c.stamp != drawStamp) {
            c.stamp = drawStamp;
            c.order = keyPoseCaches++;
        }
        const int slots = k.blend != 0.0f ? 2 : 1;  // intermittent: row[1] is not read
        for (int s = 0; s < slots; ++s) {
            const std::uint32_t row = k.row[s], pose = k.pose[s];
            const auto which = [s] { return "key-pose " + std::to_string(s); };  // built on failure only
            if (row >= rows)
                fail(which() + " is in row " + std::to_string(row) + " but its source's cache has " + std::to_string(rows) + " rows");
            if (pose >= poses)
                fail(which() + " is pose " + std::to_string(pose) + " but its source has " + std::to_string(poses) + " poses");
            if (c.wantStamp[row] == drawStamp) {
                if (c.wantPose[row] != pose || c.wantSkin[row] != k.skin)
                    fail("wants pose " + std::to_string(pose) + " (skin " + std::to_string(k.skin) + ") in row " +
                         std::to_string(row) + ", where item " + std::to_string(c.wantItem[row]) + " of the list wants pose " +
                         std::to_string(c.wantPose[row]) + " (skin " + std::to_string(c.wantSkin[row]) + ")");
                continue;
            }
            const std::span<const glm::mat4> posePalette = k.source->palette(k.skin, pose);
            if (posePalette.size() < e.gpu.requiredPalette)
                fail("the palette of skin " + std::to_string(k.skin) + " in pose " + std::to_string(pose) + " has " +
                     std::to_string(posePalette.size()) + " matrices but its mesh's joint indices need " +
                     std::to_string(e.gpu.requiredPalette));
            c.wantStamp[row] = drawStamp;
            c.wantPose[row] = pose;
            c.wantSkin[row] = k.skin;
            c.wantItem[row] = i;
            if (c.heldPose[row] != pose || c.heldSkin[row] != k.skin)
                fills.push_back(KeyPoseFill{&c, &e, row, pose, k.skin, posePalette.data(), 0});
        }
        return c;
    }

    // Skins the scheduled rows into their caches (transform feedback of the skinning vertex
    // shader, rasteriser off): one instanced draw per run of consecutive rows of one cache, each
    // instance with its own palette. The palette buffer and the instance buffer are filled.
    void fillKeyPoses() {
        gl.ActiveTexture(GL_TEXTURE0 + detail::kPaletteUnit);
        gl.BindTexture(GL_TEXTURE_BUFFER, paletteTexture);
        gl.Enable(GL_RASTERIZER_DISCARD);
        gl.BindBuffer(GL_ARRAY_BUFFER, instanceBuffer);
        for (std::size_t f = 0; f < fills.size();) {
            KeyPoseGpu& c = *fills[f].cache;
            MeshEntry& e = *fills[f].mesh;
            const std::size_t rowBytes = std::size_t(e.gpu.vertexCount) * detail::kKeyPoseVertexBytes;
            if (!c.buffer || c.bytes != rowBytes * c.rows) {  // first fill, or the source changed shape
                if (!c.buffer) gl.GenBuffers(1, &c.buffer);
                if (!c.texture) gl.GenTextures(1, &c.texture);
                gl.BindBuffer(GL_TEXTURE_BUFFER, c.buffer);
                gl.BufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(std::max<std::size_t>(rowBytes * c.rows, 16)), nullptr,
                              GL_DYNAMIC_COPY);
                gl.ActiveTexture(GL_TEXTURE0 + detail::kKeyPoseUnit);
                gl.BindTexture(GL_TEXTURE_BUFFER, c.texture);
                gl.TexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32UI, c.buffer);
                keyPoseBytes += rowBytes * c.rows - c.bytes;
                c.bytes = rowBytes * c.rows;
            }
            std::size_t end = f + 1;  // the run: consecutive rows of the same cache
            while (end < fills.size() && fills[end].cache == &c && fills[end].row == fills[end - 1].row + 1) ++end;
            const auto count = static_cast<GLsizei>(end - f);
            const int k = e.gpu.influences == 8 ? 1 : 0;
            gl.UseProgram(fillPrograms[k]->id());
            gl.Uniform1i(fillBase[k], static_cast<GLint>(fills[f].paletteBase));
            gl.Uniform1i(fillStride[k], static_cast<GLint>(e.gpu.requiredPalette));
            gl.BindVertexArray(e.gpu.vao);
            pointInstanceAttributes(0);  // unread, but enabled arrays must point at a buffer
            if (e.gpu.vertexCount > 0) {
                gl.BindBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, c.buffer, static_cast<GLintptr>(rowBytes * fills[f].row),
                                   static_cast<GLsizeiptr>(rowBytes * std::size_t(count)));
                gl.BeginTransformFeedback(GL_POINTS);
                gl.DrawArraysInstanced(GL_POINTS, 0, static_cast<GLsizei>(e.gpu.vertexCount), count);
                gl.EndTransformFeedback();
                ++stats.keyPoseFillCalls;
            }
            for (std::size_t g = f; g < end; ++g) {
                c.heldPose[fills[g].row] = fills[g].pose;
                c.heldSkin[fills[g].row] = fills[g].skin;
            }
            stats.keyPoseFills += std::uint64_t(count);
            f = end;
        }
        gl.BindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, 0);
        gl.Disable(GL_RASTERIZER_DISCARD);
        gl.BindVertexArray(0);
        gl.UseProgram(0);
        stats.keyPoseCacheBytes = keyPoseBytes;
    }

    // Makes a stream buffer hold at least `bytes`, growing it geometrically. Storage is reallocated
    // only when it grows: re-specifying it every frame (orphaning) makes llvmpipe allocate and
    // page in megabytes per frame, which cost more than the drawing; BufferSubData on the existing
    // storage is synchronised by GL either way.
    void reserveStream(GLenum target, GLuint buffer, std::size_t& capacity, std::size_t bytes) {
        gl.BindBuffer(target, buffer);
        if (bytes <= capacity) return;
        capacity = std::max(bytes, capacity * 2);
        gl.BufferData(target, static_cast<GLsizeiptr>(capacity), nullptr, GL_STREAM_DRAW);
    }

    void loadFrameUniforms(ProgramState& p) {
        const glm::vec3 light = glm::length(options.lightDirection) > 0.0f ? glm::normalize(options.lightDirection)
                                                                            : glm::vec3(0.0f, 1.0f, 0.0f);
        gl.UniformMatrix4fv(p.viewRotation, 1, GL_FALSE, &viewRotation[0][0]);
        gl.UniformMatrix4fv(p.projection, 1, GL_FALSE, &projection[0][0]);
        gl.Uniform3fv(p.lightDirection, 1, &light[0]);
        gl.Uniform3fv(p.lightColor, 1, &options.lightColor[0]);
        gl.Uniform3fv(p.skyColor, 1, &options.skyColor[0]);
        gl.Uniform3fv(p.groundColor, 1, &options.groundColor[0]);
        gl.Uniform1i(p.flatTint, options.flatTint);
        gl.Uniform1i(p.regionIds, options.regionIds);
        p.frameStamp = frameStamp;
    }
};

GlRenderer::GlRenderer(std::shared_ptr<GlContext> context, const RendererOptions& options) {
    if (!context) throw std::invalid_argument("GlRenderer: argument 'context' is null");
    checkOptions(options, "GlRenderer");
    impl_ = std::make_unique<Impl>(std::move(context));
    Impl& r = *impl_;
    r.options = options;
    r.context->makeCurrent();
    const GladGLContext& gl = r.gl;
    const auto build = [&](ProgramState& p, const std::string& name, const std::string& vertex, const std::string& fragment) {
        r.buildProgram(p, name, vertex, fragment);
    };
    const int influences[3] = {0, 4, 8};
    for (int k = 0; k < 3; ++k)
        build(r.programs[k], std::to_string(influences[k]) + " joint influences", detail::vertexShaderSource(influences[k], false),
              detail::fragmentShaderSource());
    build(r.constantFaces, "constant faces", detail::constantFaceVertexShaderSource(), detail::constantFaceFragmentShaderSource());
    build(r.flatLight, "flat-lit faces", detail::flatLightVertexShaderSource(), detail::flatLightFragmentShaderSource());
    build(r.keyPosePrograms[0], "key-pose, one row", detail::keyPoseVertexShaderSource(false), detail::fragmentShaderSource());
    build(r.keyPosePrograms[1], "key-pose, two rows blended", detail::keyPoseVertexShaderSource(true),
          detail::fragmentShaderSource());
    const char* const fillVaryings[] = {"tfCache"};
    for (int k = 0; k < 2; ++k) {
        const int n = k == 0 ? 4 : 8;
        r.fillPrograms[k] = std::make_unique<ShaderProgram>(
            *r.context, "GlRenderer shader (key-pose fill, " + std::to_string(n) + " joint influences)",
            detail::keyPoseFillVertexShaderSource(n), std::string(), fillVaryings);
        const ShaderProgram& s = *r.fillPrograms[k];
        gl.UseProgram(s.id());
        gl.Uniform1i(s.uniformLocation("uPalette"), detail::kPaletteUnit);
        r.fillBase[k] = s.uniformLocation("uFeedbackBase");
        r.fillStride[k] = s.uniformLocation("uFeedbackStride");
    }
    gl.UseProgram(0);
    gl.GenBuffers(1, &r.instanceBuffer);
    gl.GenBuffers(1, &r.streamBuffer);
    gl.GenBuffers(1, &r.paletteBuffer);
    gl.BindBuffer(GL_TEXTURE_BUFFER, r.paletteBuffer);
    r.paletteCapacity = 64 * sizeof(glm::mat4);
    gl.BufferData(GL_TEXTURE_BUFFER, static_cast<GLsizeiptr>(r.paletteCapacity), nullptr, GL_STREAM_DRAW);
    gl.GenTextures(1, &r.paletteTexture);
    gl.BindTexture(GL_TEXTURE_BUFFER, r.paletteTexture);
    gl.TexBuffer(GL_TEXTURE_BUFFER, GL_RGBA32F, r.paletteBuffer);
    gl.GetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &r.maxTextureBufferTexels);
    // A white texel stands in for meshes without a texture, so unit 0 never samples nothing.
    const unsigned char white[4] = {255, 255, 255, 255};
    gl.GenTextures(1, &r.whiteTexture);
    gl.BindTexture(GL_TEXTURE_2D, r.whiteTexture);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_SRGB8_ALPHA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, white);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    if (options.width > 0 || options.height > 0)
        setViewportSize(options.width > 0 ? options.width : width(), options.height > 0 ? options.height : height());
}

GlRenderer::~GlRenderer() {
    Impl& r = *impl_;
    try {
        r.context->makeCurrent();
    } catch (...) {
        return;  // the context is unusable; destroying it frees everything
    }
    const GladGLContext& gl = r.gl;
    for (auto& [key, entry] : r.meshes) r.destroyEntry(*entry);
    for (auto& [key, texture] : r.textures) gl.DeleteTextures(1, &texture.name);
    const GLuint buffers[] = {r.instanceBuffer, r.streamBuffer, r.paletteBuffer, r.morphWeightBuffer};
    gl.DeleteBuffers(4, buffers);  // zero names are ignored
    const GLuint textures[] = {r.paletteTexture, r.whiteTexture, r.morphWeightTexture};
    gl.DeleteTextures(3, textures);
    if (r.fragmentQuery) gl.DeleteQueries(1, &r.fragmentQuery);
}

void GlRenderer::beginFrame(const Camera& camera) {
    Impl& r = *impl_;
    r.context->makeCurrent();
    const GladGLContext& gl = r.gl;
    r.stats = RenderStatistics{};
    r.stats.keyPoseCacheBytes = r.keyPoseBytes;
    ++r.frameStamp;
    r.inFrame = true;
    // Camera-relative rendering: view = R * T(-eye), so view * T(eye) is the rotation alone, and
    // model matrices get T(-eye) in double precision before they are rounded to float.
    r.eye = camera.eye();
    Mat4 rotation = camera.view() * glm::translate(Mat4(1.0), r.eye);
    rotation[3] = Vec4(0.0, 0.0, 0.0, 1.0);
    r.viewRotation = glm::mat4(rotation);
    r.projection = glm::mat4(camera.projection());

    const GlContext::DrawTarget target = r.context->drawTarget();
    gl.BindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
    gl.Viewport(target.x, target.y, target.width, target.height);
    gl.Enable(GL_DEPTH_TEST);
    gl.DepthFunc(GL_LESS);
    gl.DepthMask(GL_TRUE);
    gl.Disable(GL_BLEND);
    gl.FrontFace(GL_CCW);
    if (r.options.cullBackFaces) {
        gl.Enable(GL_CULL_FACE);
        gl.CullFace(GL_BACK);
    } else {
        gl.Disable(GL_CULL_FACE);
    }
    // A probe's state from the frame before would also limit the clear.
    gl.Disable(GL_SCISSOR_TEST);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    if (r.options.clear) {
        const glm::vec4& c = r.options.clearColor;
        gl.ClearColor(c.r, c.g, c.b, c.a);
        gl.ClearDepth(1.0);
        gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    }
    switch (r.options.probe) {
    case DrawProbe::None: break;
    case DrawProbe::SetUpOnly:
        gl.Enable(GL_SCISSOR_TEST);
        gl.Scissor(target.x, target.y, 8, 8);
        break;
    case DrawProbe::DepthOnly: gl.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE); break;
    case DrawProbe::NoDepthRejection: gl.DepthFunc(GL_ALWAYS); break;
    case DrawProbe::OneColour: break;  // chosen per group in draw()
    }
}

void GlRenderer::draw(const DrawList& list) {
    Impl& r = *impl_;
    if (!r.inFrame) throw std::logic_error("GlRenderer::draw: called outside beginFrame() / endFrame()");
    Stopwatch watch;
    r.context->makeCurrent();
    const GladGLContext& gl = r.gl;
    if (r.options.countFragments) {
        if (!r.fragmentQuery) gl.GenQueries(1, &r.fragmentQuery);
        gl.BeginQuery(GL_SAMPLES_PASSED, r.fragmentQuery);
    }
    r.items.clear();  // the list's segments, flattened once so that items are found by index
    for (const DrawItem& item : list.items()) r.items.push_back(&item);
    const std::vector<const DrawItem*>& items = r.items;
    ++r.drawStamp;
    r.lastMesh = nullptr;
    r.itemGroup.resize(items.size());
    r.groups.clear();
    r.planner.begin(r.options.instancing);
    r.fills.clear();
    r.keyPoseCaches = 0;

    // 1. Check every item and sort it into a group (first appearance in drawing order: with
    // frontToBack, groups by their nearest item), before any drawing.
    r.drawOrder.plan(items, r.eye, r.options.frontToBack);
    std::size_t paletteMatrices = 0, cpuVertices = 0, morphWeights = 0;
    for (const std::uint32_t i : r.drawOrder.order()) {
        const DrawItem& item = *items[i];
        if (!item.drawable) throw std::invalid_argument("GlRenderer::draw: item " + std::to_string(i) + " has no drawable");
        const auto* meshDrawable = dynamic_cast<const MeshDrawable*>(item.drawable);
        if (!meshDrawable) {
            r.itemGroup[i] = kNone;
            ++r.stats.skippedItems;
            continue;
        }
        if (!isFinite(item.world))
            throw std::invalid_argument("GlRenderer::draw: " + itemName(i, *item.drawable) + " has a non-finite transform");
        MeshEntry& e = r.entryFor(meshDrawable->meshPtr());
        // A mirroring matrix turns counter-clockwise triangles clockwise: such items are drawn
        // apart with the front face flipped, so culling and two-sided lighting stay right.
        const bool mirrored = glm::determinant(glm::dmat3(item.world.linear)) < 0.0;
        // Front to back, a mesh's instances are split by distance band, so that an instanced
        // draw covering the whole town does not put far instances before near ones of other meshes.
        const std::int32_t band = r.drawOrder.band()[i];
        if (item.representation == Representation::KeyPose) {
            // Grouped by mesh, cache, one row or two, mirroring and band: one instanced draw each.
            KeyPoseGpu& c = r.wantKeyPoses(i, item, e);
            const bool blended = item.keyPose.blend != 0.0f;
            bool opened = false;
            const std::uint32_t g = r.planner.join(c.batches, (blended ? 2 : 0) + (mirrored ? 1 : 0), band, opened);
            if (opened) r.groups.push_back(Group{&e, blended ? Path::KeyPoseBlend : Path::KeyPose, mirrored, 0, 0, 0, band, &c});
            r.itemGroup[i] = g;
            continue;
        }
        const bool skinned = e.gpu.influences > 0 && item.skinPalette != nullptr;
        if (skinned && item.skinPaletteSize < e.gpu.requiredPalette)
            throw std::invalid_argument("GlRenderer::draw: " + itemName(i, *item.drawable) + ": its skin palette has " +
                                        std::to_string(item.skinPaletteSize) + " matrices but its joint indices need " +
                                        std::to_string(e.gpu.requiredPalette));
        const std::uint32_t morphs = r.morphWeightsOf(i, item, e);
        morphWeights += morphs;
        // The CPU path deforms on the CPU whatever it deforms: skin, morph targets or both.
        const Path path = !skinned && !(morphs && r.options.forceCpuSkinning) ? Path::Rigid
                          : r.options.forceCpuSkinning                       ? Path::CpuSkinned
                                                                             : Path::GpuSkinned;
        if (path == Path::CpuSkinned) {
            r.itemGroup[i] = r.planner.alone(band);
            r.groups.push_back(Group{&e, path, mirrored, 1, 0, static_cast<std::uint32_t>(cpuVertices), band});
            cpuVertices += e.gpu.vertexCount;
            continue;
        }
        if (path == Path::GpuSkinned) paletteMatrices += e.gpu.requiredPalette;
        bool opened = false;
        const std::uint32_t g = r.planner.join(e.batches, (path == Path::GpuSkinned ? 2 : 0) + (mirrored ? 1 : 0), band, opened);
        if (opened) r.groups.push_back(Group{&e, path, mirrored, 0, 0, 0, band});
        r.itemGroup[i] = g;
    }
    // Rows to skin, cache by cache in order of first appearance, rows ascending (runs of
    // consecutive rows are skinned by one draw); their palettes follow the items' in the buffer.
    std::sort(r.fills.begin(), r.fills.end(), [](const KeyPoseFill& a, const KeyPoseFill& b) {
        return a.cache->order != b.cache->order ? a.cache->order < b.cache->order : a.row < b.row;
    });
    for (KeyPoseFill& f : r.fills) {
        f.paletteBase = static_cast<std::uint32_t>(paletteMatrices);
        paletteMatrices += f.mesh->gpu.requiredPalette;
    }
    if (paletteMatrices * 4 > static_cast<std::size_t>(r.maxTextureBufferTexels))
        throw std::runtime_error("GlRenderer::draw: the list's skin palettes need " + std::to_string(paletteMatrices * 4) +
                                 " texels, more than this GL's texture buffer limit of " +
                                 std::to_string(r.maxTextureBufferTexels));

    // 2. Lay the groups out in the instance buffer, then fill it in drawing order.
    const std::uint32_t slots = r.planner.layOut();
    for (std::size_t k = 0; k < r.groups.size(); ++k) {
        r.groups[k].first = r.planner.batches()[k].first;
        r.groups[k].count = r.planner.batches()[k].count;
    }
    r.instances.resize(slots);
    r.palette.resize(paletteMatrices);
    for (const KeyPoseFill& f : r.fills) std::copy_n(f.palette, f.mesh->gpu.requiredPalette, r.palette.data() + f.paletteBase);
    r.cpuPositions.resize(cpuVertices);
    r.cpuNormals.resize(cpuVertices);
    r.morphWeights.clear();
    r.morphWeights.reserve(morphWeights);
    std::size_t paletteCursor = 0;  // the items' palettes come first, then the fills'
    const Vec3 eye = r.eye;
    for (const std::uint32_t i : r.drawOrder.order()) {
        if (r.itemGroup[i] == kNone) continue;
        const DrawItem& item = *items[i];
        const Group& g = r.groups[r.itemGroup[i]];
        InstanceData& d = r.instances[r.planner.nextSlot(r.itemGroup[i])];
        detail::writeInstance(d, item, eye);
        if (g.mesh->gpu.morphTargets && item.morphWeights && g.path != Path::CpuSkinned) {
            // Only the non-zero weights, in target order: the shader reads nothing else.
            d.row1Base = static_cast<std::int32_t>(r.morphWeights.size());
            for (std::uint32_t k = 0; k < g.mesh->gpu.morphTargets; ++k) {
                const float w = std::clamp(item.morphWeights[k], -kMaxMorphWeight, kMaxMorphWeight);
                if (w != 0.0f) r.morphWeights.emplace_back(static_cast<float>(k), w);
            }
            const auto count = static_cast<std::int32_t>(r.morphWeights.size()) - d.row1Base;
            std::memcpy(&d.blend, &count, sizeof count);  // read as an int: the weights' count
            if (count) ++r.stats.morphInstances;
            r.stats.morphTargetsRead += static_cast<std::uint64_t>(count);
        }
        if (g.path == Path::KeyPose || g.path == Path::KeyPoseBlend) {
            const KeyPoseRef& k = item.keyPose;
            const std::uint32_t n = g.mesh->gpu.vertexCount;  // rows * n fits the texel limit, checked above
            d.paletteBase = static_cast<std::int32_t>(k.row[0] * n);
            d.row1Base = static_cast<std::int32_t>((g.path == Path::KeyPoseBlend ? k.row[1] : k.row[0]) * n);
            d.blend = g.path == Path::KeyPoseBlend ? k.blend : 0.0f;
        } else if (g.path == Path::GpuSkinned) {
            d.paletteBase = static_cast<std::int32_t>(paletteCursor);
            std::copy_n(item.skinPalette, g.mesh->gpu.requiredPalette, r.palette.data() + paletteCursor);
            paletteCursor += g.mesh->gpu.requiredPalette;
        } else if (g.path == Path::CpuSkinned) {
            const MeshData& mesh = static_cast<const MeshDrawable*>(item.drawable)->mesh();
            const std::size_t n = mesh.vertexCount();
            const std::span<glm::vec3> positions = std::span<glm::vec3>(r.cpuPositions).subspan(g.cpuVertexBase, n);
            const std::span<glm::vec3> normals =
                mesh.normals.empty() ? std::span<glm::vec3>() : std::span<glm::vec3>(r.cpuNormals).subspan(g.cpuVertexBase, n);
            const bool morphed = g.mesh->gpu.morphTargets && item.morphWeights;
            if (morphed) {  // targets first, then the skin (applyMorphTargets clamps as the shader's weights are)
                applyMorphTargets(mesh, std::span<const float>(item.morphWeights, mesh.morphTargets.size()), positions, normals);
                for (std::uint32_t k = 0; k < g.mesh->gpu.morphTargets; ++k) r.stats.morphTargetsRead += item.morphWeights[k] != 0.0f;
                ++r.stats.morphInstances;
            }
            if (item.skinPalette && mesh.skinned())
                skinMesh(mesh, std::span<const glm::mat4>(item.skinPalette, item.skinPaletteSize), positions, normals,
                         morphed ? std::span<const glm::vec3>(positions) : std::span<const glm::vec3>(),
                         morphed ? std::span<const glm::vec3>(normals) : std::span<const glm::vec3>());
            else if (!morphed)
                std::copy(mesh.positions.begin(), mesh.positions.end(), positions.begin());
        }
    }

    // 3. One upload per stream: instances, palettes, CPU-skinned vertices.
    if (slots > 0) {
        r.reserveStream(GL_ARRAY_BUFFER, r.instanceBuffer, r.instanceCapacity, slots * sizeof(InstanceData));
        gl.BufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(slots * sizeof(InstanceData)), r.instances.data());
    }
    if (paletteMatrices > 0) {
        const std::size_t bytes = paletteMatrices * sizeof(glm::mat4);
        r.reserveStream(GL_TEXTURE_BUFFER, r.paletteBuffer, r.paletteCapacity, bytes);
        gl.BufferSubData(GL_TEXTURE_BUFFER, 0, static_cast<GLsizeiptr>(bytes), r.palette.data());
    }
    if (!r.morphWeights.empty()) {
        if (!r.morphWeightBuffer) {
            gl.GenBuffers(1, &r.morphWeightBuffer);
            gl.GenTextures(1, &r.morphWeightTexture);
        }
        const std::size_t bytes = r.morphWeights.size() * sizeof(glm::vec2);
        const std::size_t had = r.morphWeightCapacity;
        r.reserveStream(GL_TEXTURE_BUFFER, r.morphWeightBuffer, r.morphWeightCapacity, bytes);
        if (had != r.morphWeightCapacity || had == 0) {
            gl.ActiveTexture(GL_TEXTURE0 + detail::kMorphWeightUnit);
            gl.BindTexture(GL_TEXTURE_BUFFER, r.morphWeightTexture);
            gl.TexBuffer(GL_TEXTURE_BUFFER, GL_RG32F, r.morphWeightBuffer);
        }
        gl.BufferSubData(GL_TEXTURE_BUFFER, 0, static_cast<GLsizeiptr>(bytes), r.morphWeights.data());
    }
    const std::size_t cpuBlock = cpuVertices * sizeof(glm::vec3);
    if (cpuVertices > 0) {
        r.reserveStream(GL_ARRAY_BUFFER, r.streamBuffer, r.streamCapacity, 2 * cpuBlock);
        gl.BufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(cpuBlock), r.cpuPositions.data());
        gl.BufferSubData(GL_ARRAY_BUFFER, static_cast<GLintptr>(cpuBlock), static_cast<GLsizeiptr>(cpuBlock),
                         r.cpuNormals.data());
    }

    // 4. Skin the key-pose rows that do not hold what the items want, then draw the groups.
    if (!r.fills.empty()) r.fillKeyPoses();
    gl.ActiveTexture(GL_TEXTURE0 + detail::kPaletteUnit);
    gl.BindTexture(GL_TEXTURE_BUFFER, r.paletteTexture);
    gl.ActiveTexture(GL_TEXTURE0 + detail::kBaseColorUnit);
    GLuint current = 0, keyPoseTexture = 0;
    bool clockwise = false;  // beginFrame set GL_CCW
    auto useProgram = [&](ProgramState& p, const MeshEntry& e) {
        if (p.program->id() != current) {
            current = p.program->id();
            gl.UseProgram(current);
            if (p.frameStamp != r.frameStamp) r.loadFrameUniforms(p);
        }
        gl.Uniform4fv(p.baseColor, 1, &e.baseColor[0]);
        gl.Uniform1i(p.hasTexture, e.texture != 0);
        gl.Uniform1i(p.hasNormals, e.gpu.hasNormals);
    };
    // Constant faces need every drawn triangle to face the eye (their colour has no back side).
    const bool constantFaces = r.options.constantFaces && r.options.cullBackFaces && !r.options.flatTint && !r.options.regionIds;  // ID renders: one program
    const bool oneColour = r.options.probe == DrawProbe::OneColour && !r.options.flatTint && !r.options.regionIds;
    for (Group& g : r.groups) {
        MeshEntry& e = *g.mesh;
        const detail::GlMesh& m = e.gpu;
        const bool keyPose = g.path == Path::KeyPose || g.path == Path::KeyPoseBlend;
        const bool morph = m.morphTargets > 0 && (g.path == Path::Rigid || g.path == Path::GpuSkinned);
        ProgramState& p = keyPose ? r.keyPosePrograms[g.path == Path::KeyPoseBlend ? 1 : 0]
                          : morph ? r.morphProgramFor(g.path == Path::GpuSkinned ? m.influences : 0)
                                  : r.programFor(g.path == Path::GpuSkinned ? m.influences : 0);
        if (morph) {
            gl.ActiveTexture(GL_TEXTURE0 + detail::kMorphOffsetUnit);
            gl.BindTexture(GL_TEXTURE_BUFFER, m.morphTexture);
            gl.ActiveTexture(GL_TEXTURE0 + detail::kMorphWeightUnit);
            gl.BindTexture(GL_TEXTURE_BUFFER, r.morphWeightTexture);  // 0 when no item morphs: never read
            gl.ActiveTexture(GL_TEXTURE0 + detail::kBaseColorUnit);
        }
        gl.BindTexture(GL_TEXTURE_2D, e.texture ? e.texture : r.whiteTexture);
        if (g.mirrored != clockwise) {
            clockwise = g.mirrored;
            gl.FrontFace(clockwise ? GL_CW : GL_CCW);
        }
        if (g.path == Path::CpuSkinned) {
            gl.BindVertexArray(r.cpuVaoFor(e));
            gl.BindBuffer(GL_ARRAY_BUFFER, r.streamBuffer);
            const std::size_t base = static_cast<std::size_t>(g.cpuVertexBase) * sizeof(glm::vec3);
            gl.VertexAttribPointer(detail::kPosition, 3, GL_FLOAT, GL_FALSE, 0, byteOffset(base));
            if (m.hasNormals)
                gl.VertexAttribPointer(detail::kNormal, 3, GL_FLOAT, GL_FALSE, 0, byteOffset(cpuBlock + base));
            r.stats.cpuSkinnedVertices += m.vertexCount;
        } else {
            gl.BindVertexArray(m.vao);
            if (g.path == Path::GpuSkinned) r.stats.gpuSkinnedVertices += std::uint64_t(m.vertexCount) * g.count;
        }
        if (keyPose) {
            if (g.keyPose->texture != keyPoseTexture) {
                keyPoseTexture = g.keyPose->texture;
                gl.ActiveTexture(GL_TEXTURE0 + detail::kKeyPoseUnit);
                gl.BindTexture(GL_TEXTURE_BUFFER, keyPoseTexture);
                gl.ActiveTexture(GL_TEXTURE0 + detail::kBaseColorUnit);
            }
            r.stats.keyPoseInstances += g.count;
            r.stats.keyPoseVertices += std::uint64_t(m.vertexCount) * g.count * (g.path == Path::KeyPoseBlend ? 2 : 1);
        }
        r.stats.instances += g.count;
        r.stats.triangles += std::uint64_t(m.triangleCount) * g.count;
        if (m.indexCount == 0) continue;
        gl.BindBuffer(GL_ARRAY_BUFFER, r.instanceBuffer);
        r.pointInstanceAttributes(g.first);
        auto drawRange = [&](GLsizei first, GLsizei count) {
            if (count == 0) return;
            const void* at = byteOffset(static_cast<std::size_t>(first) * sizeof(std::uint32_t));
            if (g.count == 1) gl.DrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, at);
            else gl.DrawElementsInstanced(GL_TRIANGLES, count, GL_UNSIGNED_INT, at, static_cast<GLsizei>(g.count));
            ++r.stats.drawCalls;
        };
        const GLsizei classified = m.constantIndexCount + m.flatLitIndexCount;
        if (morph) {  // the shape moves: no triangle's shading is known in advance
            useProgram(p, e);
            gl.Uniform1i(p.morphVertices, static_cast<GLint>(m.vertexCount));
            drawRange(0, m.indexCount);
        } else if (oneColour && g.path == Path::Rigid) {
            useProgram(r.constantFaces, e);
            drawRange(constantFaces && classified > 0 ? m.indexCount : 0, m.indexCount);  // the order the pass itself draws
        } else if (constantFaces && g.path == Path::Rigid && classified > 0) {
            // The classified copy of the indices: constant triangles, flat-lit ones, then the rest.
            r.stats.constantTriangles += std::uint64_t(m.constantIndexCount / 3) * g.count;
            r.stats.flatLitTriangles += std::uint64_t(m.flatLitIndexCount / 3) * g.count;
            if (m.constantIndexCount > 0) useProgram(r.constantFaces, e);
            drawRange(m.indexCount, m.constantIndexCount);
            if (m.flatLitIndexCount > 0) useProgram(r.flatLight, e);
            drawRange(m.indexCount + m.constantIndexCount, m.flatLitIndexCount);
            if (classified < m.indexCount) useProgram(p, e);
            drawRange(m.indexCount + classified, m.indexCount - classified);
        } else {
            useProgram(p, e);
            drawRange(0, m.indexCount);
        }
    }
    gl.BindVertexArray(0);
    if (clockwise) gl.FrontFace(GL_CCW);
    if (r.options.countFragments) {
        gl.EndQuery(GL_SAMPLES_PASSED);
        GLuint64 passed = 0;
        gl.GetQueryObjectui64v(r.fragmentQuery, GL_QUERY_RESULT, &passed);
        r.stats.fragments += passed;
    }
    r.stats.drawMs += watch.elapsedMs();
}

void GlRenderer::endFrame() {
    Impl& r = *impl_;
    if (!r.inFrame) throw std::logic_error("GlRenderer::endFrame: no frame was begun");
    if (r.options.captureFrames) r.lastFrame = readFrame();
    r.context->present();
    r.inFrame = false;
}

void GlRenderer::setOptions(const RendererOptions& options) {
    checkOptions(options, "GlRenderer::setOptions");
    const int w = options.width > 0 ? options.width : width();
    const int h = options.height > 0 ? options.height : height();
    if (w != width() || h != height()) setViewportSize(w, h);
    impl_->options = options;
}

const RendererOptions& GlRenderer::options() const { return impl_->options; }

void GlRenderer::setViewportSize(int width, int height) {
    checkPositive(width, height, "GlRenderer::setViewportSize");
    impl_->context->resize(width, height);
}

int GlRenderer::width() const { return impl_->context->width(); }

int GlRenderer::height() const { return impl_->context->height(); }

const RenderStatistics& GlRenderer::statistics() const { return impl_->stats; }

Image GlRenderer::readFrame() {
    Impl& r = *impl_;
    r.context->makeCurrent();
    const GladGLContext& gl = r.gl;
    Image image;
    image.name = "frame";
    image.width = r.context->width();
    image.height = r.context->height();
    const std::size_t row = static_cast<std::size_t>(image.width) * 4;
    image.rgba.resize(row * static_cast<std::size_t>(image.height));
    const GLuint fbo = r.context->framebuffer();
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
    gl.ReadBuffer(fbo ? GL_COLOR_ATTACHMENT0 : GL_BACK);
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
    // GL returns the bottom row first; Image keeps the top row first.
    std::vector<std::uint8_t> swap(row);
    for (int y = 0; y < image.height / 2; ++y) {
        std::uint8_t* a = image.rgba.data() + static_cast<std::size_t>(y) * row;
        std::uint8_t* b = image.rgba.data() + static_cast<std::size_t>(image.height - 1 - y) * row;
        std::memcpy(swap.data(), a, row);
        std::memcpy(a, b, row);
        std::memcpy(b, swap.data(), row);
    }
    return image;
}

const Image& GlRenderer::lastFrame() const { return impl_->lastFrame; }

void GlRenderer::releaseUnusedResources() {
    Impl& r = *impl_;
    r.context->makeCurrent();
    r.lastMesh = nullptr;
    for (auto it = r.meshes.begin(); it != r.meshes.end();) {
        if (it->second->source.expired()) {
            r.destroyEntry(*it->second);
            it = r.meshes.erase(it);
        } else {
            ++it;
        }
    }
    for (auto it = r.textures.begin(); it != r.textures.end();) {
        if (it->second.source.expired()) {
            r.gl.DeleteTextures(1, &it->second.name);
            it = r.textures.erase(it);
        } else {
            ++it;
        }
    }
}

std::size_t GlRenderer::cachedMeshCount() const { return impl_->meshes.size(); }

std::size_t GlRenderer::cachedTextureCount() const { return impl_->textures.size(); }

void GlRenderer::releaseKeyPoses(const KeyPoseSource& source) {
    Impl& r = *impl_;
    r.context->makeCurrent();
    for (auto& [key, entry] : r.meshes) {
        auto& caches = entry->keyPoses;
        for (auto it = caches.begin(); it != caches.end();) {
            if ((*it)->source == &source) {
                r.destroyKeyPose(**it);
                it = caches.erase(it);
            } else {
                ++it;
            }
        }
    }
    if (r.inFrame) r.stats.keyPoseCacheBytes = r.keyPoseBytes;
}

std::size_t GlRenderer::cachedKeyPoseCount() const {
    std::size_t n = 0;
    for (const auto& [key, entry] : impl_->meshes)
        for (const auto& c : entry->keyPoses) n += c->buffer != 0;
    return n;
}

std::size_t GlRenderer::keyPoseCacheBytes() const { return impl_->keyPoseBytes; }

GlContext& GlRenderer::context() const { return *impl_->context; }

}  // namespace throng
