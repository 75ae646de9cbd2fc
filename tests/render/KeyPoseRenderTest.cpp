// Key-pose items in GlRenderer (seed 004 §3 and §5): skinned key-poses kept in GPU rows per (mesh,
// KeyPoseSource), filled by the renderer's own skinning (transform feedback) only when a row's pose
// changes, and drawn instanced from one row (intermittent) or two rows blended (interpolative).
//
//   * A character drawn from the cache is the character drawn skinned with that key-pose's palette,
//     within the golden-image tolerance (GoldenTolerance: at most 0.5% of the pixels over 8/255,
//     PSNR >= 35 dB), for CesiumMan and the robot at several key-poses and views, mirrored too,
//     several instances in one list; a procedural tube of eight influences through a hand-made source.
//   * Interpolative: equal within that tolerance to a CPU blend of the two skinned poses (skinMesh,
//     positions blended linearly, normals blended then renormalised) drawn as a rigid mesh.
//   * Retention: a list drawn twice fills once; one row's pose changed refills that row only; a
//     second source with the same mesh gets its own cache; releaseKeyPoses frees it.
//   * Every bad key-pose item throws std::invalid_argument naming it, draws nothing and changes no
//     row record.
//   * flatTint ID renders read the tints back exactly; front-to-back bands split instanced draws;
//     CrowdRenderer draws key-pose items in the actors' mesh pass.
// Characters come from the shared assets (../shared/assets/characters beside the repository).

#include <gtest/gtest.h>

#include <optional>

#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>

#include "RenderTestSupport.h"
#include "throng/testkit/Assets.h"
#include "throng/testkit/Characters.h"
#include "throng/actors/ActorTemplate.h"
#include "throng/actors/KeyPoseCache.h"
#include "throng/gltf/GltfLoader.h"
#include "throng/render/CpuSkinning.h"
#include "throng/render/CrowdRenderer.h"
#include "throng/render/GlRenderer.h"
#include "throng/render/OsMesaContext.h"
#include "throng/render/ProceduralMeshes.h"
#include "throng/scenegraph/MeshDrawable.h"

namespace throng {
namespace {

constexpr int kSize = 160;  // square frames, as the character goldens

const test::GoldenTolerance kGolden{};  // the project's golden-image tolerance

// Each file is loaded once for the whole test program.
const CharacterAsset& asset(const std::string& file) { return testkit::sharedCharacter(file); }

// A character's template, its highest-detail skinned mesh and that mesh's skin.
struct Character {
    std::shared_ptr<const ActorTemplate> tmpl;
    std::shared_ptr<const MeshDrawable> drawable;
    std::uint32_t skin = 0;
    const MeshData& mesh() const { return drawable->mesh(); }
};

Character character(const std::string& file) {
    Character c;
    c.tmpl = asset(file).primaryTemplate();
    if (!c.tmpl) throw std::runtime_error(file + ": no template");
    for (const VaLodLevel& level : c.tmpl->rootGeometry().levels())
        if (level.skin >= 0)
            if (auto d = std::dynamic_pointer_cast<const MeshDrawable>(level.drawable)) {
                c.drawable = d;
                c.skin = static_cast<std::uint32_t>(level.skin);
                break;
            }
    if (!c.drawable) throw std::runtime_error(file + ": no skinned mesh");
    return c;
}

using test::disagreement;

// A camera from `azimuthDeg` (about +Y from +Z) and `elevationDeg` framing `mesh` posed by `palette`
// and placed by `world`.
Camera frameOn(const MeshData& mesh, std::span<const glm::mat4> palette, const Mat4& world, double azimuthDeg,
               double elevationDeg) {
    std::vector<glm::vec3> posed(mesh.vertexCount());
    skinMesh(mesh, palette, posed, {});
    Vec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
    for (const glm::vec3& p : posed) {
        const Vec3 w(world * Vec4(Vec3(p), 1.0));
        lo = glm::min(lo, w);
        hi = glm::max(hi, w);
    }
    const Vec3 centre = 0.5 * (lo + hi);
    const double d = 1.4 * glm::length(hi - lo);
    const double a = azimuthDeg * std::numbers::pi / 180.0, e = elevationDeg * std::numbers::pi / 180.0;
    Camera camera;
    camera.setPerspective(std::numbers::pi / 4.0, 1.0, 0.02 * d, 10.0 * d);
    camera.setLookAt(centre + d * Vec3(std::sin(a) * std::cos(e), std::sin(e), std::cos(a) * std::cos(e)), centre);
    return camera;
}

// A key-pose item of `c`'s mesh showing `pose0` from `row0`, or blended towards `pose1` in `row1`.
DrawItem keyPoseItem(const Character& c, const KeyPoseSource* source, std::uint32_t pose0, std::uint32_t row0,
                     std::uint32_t pose1, std::uint32_t row1, float blend, const glm::vec4& tint = glm::vec4(1.0f)) {
    DrawItem item;
    item.drawable = c.drawable.get();
    item.representation = Representation::KeyPose;
    item.actor = 0;
    item.tint = tint;
    item.keyPose.source = source;
    item.keyPose.skin = c.skin;
    item.keyPose.pose[0] = pose0;
    item.keyPose.pose[1] = pose1;
    item.keyPose.row[0] = row0;
    item.keyPose.row[1] = row1;
    item.keyPose.blend = blend;
    return item;
}

DrawItem intermittentItem(const Character& c, const KeyPoseSource* source, std::uint32_t pose, std::uint32_t row,
                          const glm::vec4& tint = glm::vec4(1.0f)) {
    return keyPoseItem(c, source, pose, row, pose, row, 0.0f, tint);
}

// Appends `item` with its own copy of `world` (and of `palette`, for a skinned item).
void add(DrawList& list, DrawItem item, const Mat4& world, std::span<const glm::mat4> palette = {}) {
    list.add(item, item.drawable->primitiveCount(), world, palette);
}

// Appends `c` drawn skinned with `palette`.
void addSkinned(DrawList& list, const Character& c, const Mat4& world, std::span<const glm::mat4> palette,
                const glm::vec4& tint = glm::vec4(1.0f)) {
    DrawItem item;
    item.drawable = c.drawable.get();
    item.actor = 0;
    item.tint = tint;
    add(list, item, world, palette);
}

Image render(GlRenderer& renderer, const Camera& camera, const DrawList& list) {
    renderer.beginFrame(camera);
    renderer.draw(list);
    Image image = renderer.readFrame();
    renderer.endFrame();
    return image;
}

// `mesh` posed as the blend of two skinned poses, as a rigid mesh (no skin): what an interpolated
// key-pose item shows, computed on the CPU.
std::shared_ptr<MeshData> cpuBlend(const MeshData& mesh, std::span<const glm::mat4> a, std::span<const glm::mat4> b,
                                   float blend) {
    const std::size_t n = mesh.vertexCount();
    std::vector<glm::vec3> pa(n), pb(n), na(n), nb(n);
    skinMesh(mesh, a, pa, na);
    skinMesh(mesh, b, pb, nb);
    auto out = std::make_shared<MeshData>();
    out->name = mesh.name + " (CPU blend)";
    out->positions.resize(n);
    out->normals.resize(mesh.normals.empty() ? 0 : n);
    for (std::size_t v = 0; v < n; ++v) {
        out->positions[v] = pa[v] + (pb[v] - pa[v]) * blend;
        if (!mesh.normals.empty()) {
            const glm::vec3 m = na[v] * (1.0f - blend) + nb[v] * blend;
            out->normals[v] = glm::length(m) > 0.0f ? glm::normalize(m) : nb[v];
        }
    }
    out->texcoords = mesh.texcoords;
    out->indices = mesh.indices;
    out->baseColor = mesh.baseColor;
    out->baseColorTexture = mesh.baseColorTexture;
    return out;
}

// A source of hand-made palettes (any KeyPoseSource works, not only the actors' cache).
class PaletteSource final : public KeyPoseSource {
public:
    PaletteSource(std::uint32_t rows, std::vector<std::vector<glm::mat4>> poses) : rows_(rows), poses_(std::move(poses)) {}
    std::uint32_t rowCount() const override { return rows_; }
    std::uint32_t poseCount() const override { return static_cast<std::uint32_t>(poses_.size()); }
    std::span<const glm::mat4> palette(std::uint32_t skin, std::uint32_t pose) const override {
        if (skin != 0 || pose >= poses_.size()) return {};
        return poses_[pose];
    }

private:
    std::uint32_t rows_;
    std::vector<std::vector<glm::mat4>> poses_;
};

// Another source's palettes cut to `keep` matrices.
class ShortSource final : public KeyPoseSource {
public:
    ShortSource(const KeyPoseSource& inner, std::size_t keep) : inner_(inner), keep_(keep) {}
    std::uint32_t rowCount() const override { return inner_.rowCount(); }
    std::uint32_t poseCount() const override { return inner_.poseCount(); }
    std::span<const glm::mat4> palette(std::uint32_t skin, std::uint32_t pose) const override {
        const auto p = inner_.palette(skin, pose);
        return p.first(std::min(p.size(), keep_));
    }

private:
    const KeyPoseSource& inner_;
    std::size_t keep_;
};

class KeyPoseRenderTest : public ::testing::Test {
protected:
    std::shared_ptr<OsMesaContext> context = std::make_shared<OsMesaContext>(kSize, kSize);
};

// Clip of the character's walk (the robot's first clip is not a walk).
int walkClip(const Character& c, const std::string& file) {
    return file == "robot.glb" ? c.tmpl->findClip("Robot_Walking") : 0;
}

TEST_F(KeyPoseRenderTest, IntermittentMatchesSkinningAtTheKeyPose) {
    struct View {
        double azimuth, elevation;
    };
    const View views[] = {{30.0, 10.0}, {150.0, 25.0}, {-95.0, 0.0}};
    for (const char* file : {"CesiumMan.glb", "robot.glb"}) {
        SCOPED_TRACE(file);
        ASSERT_TRUE(std::filesystem::exists(testkit::characterPath(file))) << testkit::characterPath(file) << " is missing";
        const Character c = character(file);
        const int clip = walkClip(c, file);
        ASSERT_GE(clip, 0);
        KeyPoseCacheSettings settings;
        settings.rows = 4;
        const KeyPoseCache cache(c.tmpl, settings);
        GlRenderer renderer(context);
        const std::uint32_t first = cache.firstPose(clip), count = cache.posesOf(clip);
        ASSERT_GE(count, 6u);
        for (std::uint32_t k = 0; k < 3; ++k) {
            const std::uint32_t pose = first + k * count / 3;
            const std::span<const glm::mat4> palette = cache.palette(c.skin, pose);
            for (std::size_t v = 0; v < std::size(views); ++v) {
                SCOPED_TRACE("pose " + std::to_string(pose) + ", view " + std::to_string(v));
                // The last view mirrored (x -> -x): culling and two-sided lighting must follow.
                const Mat4 world = v == 2 ? glm::scale(Mat4(1.0), Vec3(-1.0, 1.0, 1.0)) : Mat4(1.0);
                const Camera camera = frameOn(c.mesh(), palette, world, views[v].azimuth, views[v].elevation);
                DrawList cached, skinned;
                add(cached, intermittentItem(c, &cache, pose, k), world);
                addSkinned(skinned, c, world, palette);
                const Image fromCache = render(renderer, camera, cached);
                const RenderStatistics s = renderer.statistics();
                EXPECT_EQ(s.keyPoseInstances, 1u);
                EXPECT_EQ(s.instances, 1u);
                EXPECT_EQ(s.drawCalls, 1u);
                EXPECT_EQ(s.triangles, c.mesh().triangleCount());
                EXPECT_EQ(s.keyPoseVertices, c.mesh().vertexCount());
                EXPECT_EQ(s.gpuSkinnedVertices, 0u);
                EXPECT_EQ(s.keyPoseFills, v == 0 ? 1u : 0u) << "the row holds its pose from the first view on";
                EXPECT_EQ(s.keyPoseCacheBytes, std::uint64_t(settings.rows) * c.mesh().vertexCount() * 16);
                const Image reference = render(renderer, camera, skinned);
                EXPECT_GT(test::coveredPixels(reference), std::size_t(kSize * kSize) / 25);
                const std::string failure = disagreement(fromCache, reference, kGolden);
                EXPECT_TRUE(failure.empty()) << "the cached key-pose is not the skinned one: " << failure;
                if (!failure.empty()) {
                    test::writeOutput(fromCache, std::string("keypose-") + file + "-cached");
                    test::writeOutput(reference, std::string("keypose-") + file + "-skinned");
                }
                // The tolerance sees a neighbouring key-pose: the comparison can fail.
                DrawList other;
                addSkinned(other, c, world, cache.palette(c.skin, first + (k * count / 3 + 2) % count));
                EXPECT_FALSE(disagreement(render(renderer, camera, other), reference, kGolden).empty())
                    << "two key-poses apart look the same: the test cannot see a wrong pose";
            }
        }
    }
}

TEST_F(KeyPoseRenderTest, InstancesOfOneMeshAndSourceAreOneDrawEachWithItsOwnRowMirroredApart) {
    const Character c = character("CesiumMan.glb");
    KeyPoseCacheSettings settings;
    settings.rows = 6;
    const KeyPoseCache cache(c.tmpl, settings);
    const std::uint32_t poses[] = {2, 9, 17, 24};
    DrawList cached, skinned;
    for (std::size_t i = 0; i < std::size(poses); ++i) {
        // The second one mirrored: drawn apart, with the front face flipped.
        const Mat4 world = glm::scale(glm::rotate(glm::translate(Mat4(1.0), Vec3(0.9 * double(i) - 1.35, 0.0, -0.4 * double(i))),
                                                  0.4 * double(i), Vec3(0.0, 1.0, 0.0)),
                                      Vec3(i == 1 ? -1.0 : 1.0, 1.0, 1.0));
        const glm::vec4 tint(1.0f, 1.0f - 0.15f * float(i), 0.8f + 0.05f * float(i), 1.0f);
        add(cached, intermittentItem(c, &cache, poses[i], std::uint32_t(5 - i), tint), world);
        addSkinned(skinned, c, world, cache.palette(c.skin, poses[i]), tint);
    }
    Camera camera;
    camera.setPerspective(std::numbers::pi / 4.0, 1.0, 0.05, 100.0);
    camera.setLookAt(Vec3(0.2, 1.6, 4.2), Vec3(0.0, 0.8, -0.6));
    GlRenderer renderer(context);
    const Image fromCache = render(renderer, camera, cached);
    EXPECT_EQ(renderer.statistics().drawCalls, 2u) << "one instanced draw, and the mirrored one apart";
    EXPECT_EQ(renderer.statistics().keyPoseInstances, 4u);
    EXPECT_EQ(renderer.statistics().keyPoseFills, 4u);
    EXPECT_EQ(renderer.statistics().keyPoseFillCalls, 1u) << "rows 2 to 5 are consecutive: one fill draw";
    const Image reference = render(renderer, camera, skinned);
    EXPECT_GT(test::coveredPixels(reference), std::size_t(kSize * kSize) / 20);
    const std::string failure = disagreement(fromCache, reference, kGolden);
    EXPECT_TRUE(failure.empty()) << failure;
    if (!failure.empty()) {
        test::writeOutput(fromCache, "keypose-instances-cached");
        test::writeOutput(reference, "keypose-instances-skinned");
    }
}

TEST_F(KeyPoseRenderTest, EightInfluencesFromAHandMadeSource) {
    SkinnedTubeOptions tube;
    tube.joints = 6;
    tube.influences = 8;
    tube.blend = 3.5f;
    tube.ringsPerBand = 25;
    tube.color = glm::vec4(0.35f, 0.45f, 0.85f, 1.0f);
    std::vector<std::vector<glm::mat4>> palettes(3);
    for (int p = 0; p < 3; ++p) bendTubePalette(tube, 0.3f * float(p - 1), palettes[std::size_t(p)], 0.2f);
    const PaletteSource source(2, palettes);
    Character c;
    c.drawable = test::drawable(makeSkinnedTube(tube));
    const Mat4 world = glm::translate(Mat4(1.0), Vec3(0.4, -1, 0));
    const Camera camera = frameOn(c.mesh(), palettes[2], world, 0.0, 0.0);
    GlRenderer renderer(context);
    for (std::uint32_t pose : {2u, 0u}) {
        DrawList cached, skinned;
        add(cached, intermittentItem(c, &source, pose, 1), world);
        addSkinned(skinned, c, world, palettes[pose]);
        const Image fromCache = render(renderer, camera, cached);
        EXPECT_EQ(renderer.statistics().keyPoseFills, 1u);
        const Image reference = render(renderer, camera, skinned);
        EXPECT_GT(test::coveredPixels(reference), 700u);
        const std::string failure = disagreement(fromCache, reference, kGolden);
        EXPECT_TRUE(failure.empty()) << "pose " << pose << ": " << failure;
    }
}

TEST_F(KeyPoseRenderTest, InterpolativeMatchesACpuBlendOfTheTwoPoses) {
    for (const char* file : {"CesiumMan.glb", "robot.glb"}) {
        SCOPED_TRACE(file);
        const Character c = character(file);
        const int clip = walkClip(c, file);
        ASSERT_GE(clip, 0);
        KeyPoseCacheSettings settings;
        settings.rows = 8;
        settings.mode = KeyPoseMode::Interpolative;
        const KeyPoseCache cache(c.tmpl, settings);
        const std::uint32_t first = cache.firstPose(clip), count = cache.posesOf(clip);
        GlRenderer renderer(context);
        struct Case {
            std::uint32_t a, b;
            float blend;
            double azimuth, elevation;
        };
        // Poses several keys apart, so that the blend is far from either.
        const Case cases[] = {{first + 1, first + 5, 0.35f, 30.0, 10.0}, {first + count / 2, first + count / 2 + 4, 0.8f, -70.0, 15.0}};
        for (const Case& k : cases) {
            SCOPED_TRACE("poses " + std::to_string(k.a) + " and " + std::to_string(k.b) + ", blend " + std::to_string(k.blend));
            const auto pa = cache.palette(c.skin, k.a), pb = cache.palette(c.skin, k.b);
            const Camera camera = frameOn(c.mesh(), pa, Mat4(1.0), k.azimuth, k.elevation);
            DrawList cached, blended, poseA;
            add(cached, keyPoseItem(c, &cache, k.a, 3, k.b, 6, k.blend), Mat4(1.0));
            DrawItem rigid;
            const auto mesh = test::drawable(cpuBlend(c.mesh(), pa, pb, k.blend));
            rigid.drawable = mesh.get();
            add(blended, rigid, Mat4(1.0));
            addSkinned(poseA, c, Mat4(1.0), pa);
            const Image fromCache = render(renderer, camera, cached);
            EXPECT_EQ(renderer.statistics().keyPoseVertices, 2 * c.mesh().vertexCount()) << "two rows read per vertex";
            EXPECT_EQ(renderer.statistics().drawCalls, 1u);
            const Image reference = render(renderer, camera, blended);
            EXPECT_GT(test::coveredPixels(reference), std::size_t(kSize * kSize) / 25);
            const std::string failure = disagreement(fromCache, reference, kGolden);
            EXPECT_TRUE(failure.empty()) << "the blended key-poses are not the CPU blend: " << failure;
            if (!failure.empty()) {
                test::writeOutput(fromCache, std::string("keypose-blend-") + file + "-cached");
                test::writeOutput(reference, std::string("keypose-blend-") + file + "-cpu");
            }
            // The blend is seen: the first pose alone is another picture.
            EXPECT_FALSE(disagreement(render(renderer, camera, poseA), reference, kGolden).empty())
                << "the blend looks like its first pose: the test cannot see a wrong blend";
        }
    }
}

TEST_F(KeyPoseRenderTest, RowsAreRetainedAcrossFramesAndRefilledOnlyWhenTheirPoseChanges) {
    const Character c = character("CesiumMan.glb");
    KeyPoseCacheSettings settings;
    settings.rows = 8;
    const KeyPoseCache cache(c.tmpl, settings);
    const std::uint64_t bytesPerCache = std::uint64_t(settings.rows) * c.mesh().vertexCount() * GlRenderer::kKeyPoseVertexBytes;
    const auto world = [](int i) { return glm::translate(Mat4(1.0), Vec3(0.8 * i - 1.6, 0.0, 0.0)); };
    // Five actors, four rows: two actors share row 1 (the same pose, one fill).
    const std::uint32_t rows[] = {0, 1, 2, 3, 1};
    std::uint32_t poses[] = {3, 8, 13, 18, 8};
    const auto list = [&](const KeyPoseSource& source) {
        DrawList l;
        for (int i = 0; i < 5; ++i) add(l, intermittentItem(c, &source, poses[i], rows[i]), world(i));
        return l;
    };
    const auto skinnedList = [&] {
        DrawList l;
        for (int i = 0; i < 5; ++i) addSkinned(l, c, world(i), cache.palette(c.skin, poses[i]));
        return l;
    };
    Camera camera;
    camera.setPerspective(std::numbers::pi / 4.0, 1.0, 0.05, 100.0);
    camera.setLookAt(Vec3(0.0, 1.2, 5.0), Vec3(0.0, 0.8, 0.0));
    GlRenderer renderer(context);
    EXPECT_EQ(renderer.keyPoseCacheBytes(), 0u);

    const Image first = render(renderer, camera, list(cache));
    EXPECT_EQ(renderer.statistics().keyPoseFills, 4u);
    EXPECT_EQ(renderer.statistics().keyPoseInstances, 5u);
    EXPECT_EQ(renderer.statistics().keyPoseCacheBytes, bytesPerCache);
    EXPECT_EQ(renderer.cachedKeyPoseCount(), 1u);
    const Image again = render(renderer, camera, list(cache));
    EXPECT_EQ(renderer.statistics().keyPoseFills, 0u) << "the rows hold their poses: nothing to skin";
    EXPECT_EQ(renderer.statistics().keyPoseFillCalls, 0u);
    EXPECT_EQ(renderer.statistics().keyPoseCacheBytes, bytesPerCache);
    EXPECT_TRUE(disagreement(first, again, {0, 0.0, 0.0}).empty());
    EXPECT_TRUE(disagreement(first, render(renderer, camera, skinnedList()), kGolden).empty());

    // Actor 2 moves on to another pose in its row: that row alone is skinned again, and every actor
    // still shows its own pose (the other rows were kept, not refilled).
    poses[2] = 27;
    const Image changed = render(renderer, camera, list(cache));
    EXPECT_EQ(renderer.statistics().keyPoseFills, 1u);
    const std::string failure = disagreement(changed, render(renderer, camera, skinnedList()), kGolden);
    EXPECT_TRUE(failure.empty()) << failure;
    EXPECT_FALSE(disagreement(changed, first, kGolden).empty()) << "the new pose is not drawn";
    render(renderer, camera, list(cache));
    EXPECT_EQ(renderer.statistics().keyPoseFills, 0u);

    // A second source of the same template and mesh: a cache of its own, filled for its own rows,
    // and the first source's rows are untouched by it.
    const KeyPoseCache other(c.tmpl, settings);
    render(renderer, camera, list(other));
    EXPECT_EQ(renderer.statistics().keyPoseFills, 4u);
    EXPECT_EQ(renderer.cachedKeyPoseCount(), 2u);
    EXPECT_EQ(renderer.statistics().keyPoseCacheBytes, 2 * bytesPerCache);
    DrawList both = list(cache);
    DrawList second = list(other);
    both.append(second);
    const Image two = render(renderer, camera, both);
    EXPECT_EQ(renderer.statistics().keyPoseFills, 0u);
    EXPECT_EQ(renderer.statistics().drawCalls, 2u) << "one instanced draw per (mesh, source)";
    EXPECT_EQ(renderer.statistics().keyPoseInstances, 10u);
    EXPECT_TRUE(disagreement(two, changed, {0, 0.0, 0.0}).empty()) << "the same actors drawn twice at the same places";

    // Freeing the second source's cache: the first keeps its rows.
    renderer.releaseKeyPoses(other);
    EXPECT_EQ(renderer.cachedKeyPoseCount(), 1u);
    EXPECT_EQ(renderer.keyPoseCacheBytes(), bytesPerCache);
    render(renderer, camera, list(cache));
    EXPECT_EQ(renderer.statistics().keyPoseFills, 0u);
    render(renderer, camera, list(other));
    EXPECT_EQ(renderer.statistics().keyPoseFills, 4u);

    // An interpolated item adds the second row it reads, once.
    DrawList blended = list(cache);
    add(blended, keyPoseItem(c, &cache, poses[0], rows[0], 22, 7, 0.5f), world(2));
    render(renderer, camera, blended);
    EXPECT_EQ(renderer.statistics().keyPoseFills, 1u);
    render(renderer, camera, blended);
    EXPECT_EQ(renderer.statistics().keyPoseFills, 0u);

    // A new source made where a freed one lived (same address, same shape) is another source: its
    // rows are skinned afresh, not read from what the old one left.
    std::optional<KeyPoseCache> reborn(std::in_place, c.tmpl, settings);
    const KeyPoseSource* address = &*reborn;
    render(renderer, camera, list(*reborn));
    EXPECT_EQ(renderer.statistics().keyPoseFills, 4u);
    reborn.emplace(c.tmpl, settings);
    ASSERT_EQ(&*reborn, address);
    render(renderer, camera, list(*reborn));
    EXPECT_EQ(renderer.statistics().keyPoseFills, 4u) << "a new source at a freed one's address";
}

TEST_F(KeyPoseRenderTest, BadKeyPoseItemsThrowNamingTheItemAndDrawNothing) {
    const Character c = character("CesiumMan.glb");
    KeyPoseCacheSettings settings;
    settings.rows = 8;
    const KeyPoseCache cache(c.tmpl, settings);
    const ShortSource shortPalettes(cache, 3);
    const auto quad = test::drawable(makeQuad(1.0f, 1.0f));
    const std::uint32_t poses = cache.poseCount();
    ASSERT_GT(c.mesh().vertexCount(), 0u);
    struct Case {
        const char* what;
        DrawItem bad;
        std::string message;
    };
    std::vector<Case> cases;
    DrawItem noSource = intermittentItem(c, &cache, 1, 1);
    noSource.keyPose.source = nullptr;
    cases.push_back({"null source", noSource, "item 1 (drawable '" + c.drawable->name() + "'): a key-pose item without a source"});
    cases.push_back({"row outside", intermittentItem(c, &cache, 1, 8), "item 1 (drawable '" + c.drawable->name() +
                                                                          "'): key-pose 0 is in row 8 but its source's cache has 8 rows"});
    cases.push_back({"second row outside", keyPoseItem(c, &cache, 1, 1, 2, 9, 0.5f), "key-pose 1 is in row 9 but its source's cache has 8 rows"});
    cases.push_back({"pose outside", intermittentItem(c, &cache, poses, 1),
                     "key-pose 0 is pose " + std::to_string(poses) + " but its source has " + std::to_string(poses) + " poses"});
    cases.push_back({"rows in conflict", intermittentItem(c, &cache, 5, 0),
                     "item 1 (drawable '" + c.drawable->name() + "'): wants pose 5 (skin 0) in row 0, where item 0 of the list wants pose 4 (skin 0)"});
    cases.push_back({"one item's two poses in one row", keyPoseItem(c, &cache, 1, 2, 6, 2, 0.5f),
                     "wants pose 6 (skin 0) in row 2, where item 1 of the list wants pose 1"});
    cases.push_back({"short palette", intermittentItem(c, &shortPalettes, 1, 1),
                     "the palette of skin 0 in pose 1 has 3 matrices but its mesh's joint indices need"});
    DrawItem badSkin = intermittentItem(c, &cache, 1, 1);
    badSkin.keyPose.skin = 7;
    cases.push_back({"skin outside", badSkin, "the palette of skin 7 in pose 1 has 0 matrices"});
    DrawItem rigid = intermittentItem(c, &cache, 1, 1);
    rigid.drawable = quad.get();
    cases.push_back({"mesh without skin", rigid, "(drawable '" + quad->name() + "'): a key-pose item whose mesh '" +
                                                     quad->mesh().name + "' has no skin"});
    cases.push_back({"blend above 1", keyPoseItem(c, &cache, 1, 1, 2, 2, 1.5f), "key-pose blend 1.5"});
    cases.push_back({"blend NaN", keyPoseItem(c, &cache, 1, 1, 2, 2, std::numeric_limits<float>::quiet_NaN()), "is not in [0, 1]"});

    GlRenderer renderer(context);
    const Camera camera = frameOn(c.mesh(), cache.palette(c.skin, 4), Mat4(1.0), 20.0, 10.0);
    for (const Case& k : cases) {
        SCOPED_TRACE(k.what);
        DrawList list;
        add(list, intermittentItem(c, &cache, 4, 0), Mat4(1.0));  // a good item first
        add(list, k.bad, Mat4(1.0));
        renderer.beginFrame(camera);
        try {
            renderer.draw(list);
            ADD_FAILURE() << "no exception";
        } catch (const std::invalid_argument& e) {
            EXPECT_NE(std::string(e.what()).find(k.message), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find("GlRenderer::draw: item 1"), std::string::npos) << e.what();
        }
        EXPECT_EQ(test::coveredPixels(renderer.readFrame()), 0u) << "something was drawn";
        EXPECT_EQ(renderer.statistics().keyPoseFills, 0u);
        renderer.endFrame();
    }
    // No failed list changed a row record: the good item's row is still empty, so it is filled now.
    DrawList good;
    add(good, intermittentItem(c, &cache, 4, 0), Mat4(1.0));
    EXPECT_GT(test::coveredPixels(render(renderer, camera, good)), 0u);
    EXPECT_EQ(renderer.statistics().keyPoseFills, 1u);
}

TEST_F(KeyPoseRenderTest, FlatTintIdRenderReadsTheTintsBackExactly) {
    const Character c = character("CesiumMan.glb");
    KeyPoseCacheSettings settings;
    settings.rows = 4;
    const KeyPoseCache cache(c.tmpl, settings);
    RendererOptions options;
    options.flatTint = true;
    options.clearColor = glm::vec4(0.0f);
    GlRenderer renderer(context, options);
    // Channel values k / 255 are written back as k exactly.
    const glm::u8vec4 ids[] = {{17, 200, 3, 255}, {250, 9, 77, 255}, {64, 128, 192, 255}};
    DrawList list;
    for (int i = 0; i < 3; ++i) {
        const glm::vec4 tint = glm::vec4(ids[i]) / 255.0f;
        const Mat4 world = glm::translate(Mat4(1.0), Vec3(0.9 * i - 0.9, 0.0, 0.0));
        add(list, i == 2 ? keyPoseItem(c, &cache, 2, 2, 12, 3, 0.4f, tint) : intermittentItem(c, &cache, std::uint32_t(5 * i), std::uint32_t(i), tint),
            world);
    }
    Camera camera;
    camera.setPerspective(std::numbers::pi / 4.0, 1.0, 0.05, 100.0);
    camera.setLookAt(Vec3(0.0, 1.0, 4.0), Vec3(0.0, 0.8, 0.0));
    const Image image = render(renderer, camera, list);
    std::map<std::uint32_t, std::size_t> seen;
    for (std::size_t p = 0; p < image.rgba.size(); p += 4) {
        const std::uint32_t v = std::uint32_t(image.rgba[p]) | std::uint32_t(image.rgba[p + 1]) << 8 |
                                std::uint32_t(image.rgba[p + 2]) << 16 | std::uint32_t(image.rgba[p + 3]) << 24;
        if (v != 0) ++seen[v];
    }
    for (const glm::u8vec4& id : ids) {
        const std::uint32_t v = std::uint32_t(id.r) | std::uint32_t(id.g) << 8 | std::uint32_t(id.b) << 16 | std::uint32_t(id.a) << 24;
        EXPECT_GT(seen[v], 200u) << "tint " << int(id.r) << "," << int(id.g) << "," << int(id.b) << " is (nearly) missing";
        seen.erase(v);
    }
    EXPECT_TRUE(seen.empty()) << seen.size() << " other colours in an ID render, e.g. " << seen.begin()->first;
}

TEST_F(KeyPoseRenderTest, FrontToBackBandsAndInstancingSplitKeyPoseDrawsAsOthers) {
    const Character c = character("CesiumMan.glb");
    KeyPoseCacheSettings settings;
    settings.rows = 4;
    const KeyPoseCache cache(c.tmpl, settings);
    DrawList list;  // far first in the list: drawing order is not list order
    add(list, intermittentItem(c, &cache, 3, 0), glm::translate(Mat4(1.0), Vec3(0.0, 0.0, -40.0)));
    add(list, intermittentItem(c, &cache, 3, 0), glm::translate(Mat4(1.0), Vec3(1.0, 0.0, -40.5)));
    add(list, intermittentItem(c, &cache, 9, 1), glm::translate(Mat4(1.0), Vec3(0.3, 0.0, 0.0)));
    Camera camera;
    camera.setPerspective(std::numbers::pi / 4.0, 1.0, 0.05, 200.0);
    camera.setLookAt(Vec3(0.0, 1.0, 4.0), Vec3(0.0, 0.8, -20.0));
    RendererOptions options;
    GlRenderer renderer(context, options);
    const Image banded = render(renderer, camera, list);
    EXPECT_EQ(renderer.statistics().drawCalls, 2u) << "the near actor's band, then the far ones'";
    EXPECT_EQ(renderer.statistics().instances, 3u);
    options.frontToBack = false;
    renderer.setOptions(options);
    const Image oneDraw = render(renderer, camera, list);
    EXPECT_EQ(renderer.statistics().drawCalls, 1u);
    options.instancing = false;
    renderer.setOptions(options);
    const Image separate = render(renderer, camera, list);
    EXPECT_EQ(renderer.statistics().drawCalls, 3u);
    EXPECT_EQ(renderer.statistics().triangles, 3 * c.mesh().triangleCount());
    EXPECT_TRUE(disagreement(banded, oneDraw, {0, 0.0, 0.0}).empty());
    EXPECT_TRUE(disagreement(banded, separate, {0, 0.0, 0.0}).empty());
    EXPECT_GT(test::coveredPixels(banded), 500u);
}

TEST_F(KeyPoseRenderTest, CrowdRendererDrawsKeyPoseItemsInTheActorsMeshPass) {
    const Character c = character("CesiumMan.glb");
    KeyPoseCacheSettings settings;
    settings.rows = 4;
    const KeyPoseCache cache(c.tmpl, settings);
    DrawList list;
    DrawItem a = intermittentItem(c, &cache, 3, 0);
    DrawItem b = intermittentItem(c, &cache, 7, 1);
    b.actor = kNoActor;  // a key-pose item is an actor's drawing whatever its actor field says
    add(list, a, Mat4(1.0));
    add(list, b, glm::translate(Mat4(1.0), Vec3(1.0, 0.0, 0.0)));
    CrowdRenderer crowd(context);
    Camera camera;
    camera.setPerspective(std::numbers::pi / 4.0, 1.0, 0.05, 100.0);
    camera.setLookAt(Vec3(0.5, 1.0, 4.0), Vec3(0.5, 0.8, 0.0));
    crowd.beginFrame(camera);
    crowd.draw(list);
    const Image image = crowd.readFrame();
    crowd.endFrame();
    const CrowdRenderStatistics& s = crowd.statistics();
    EXPECT_EQ(s.keyPoseItems, 2u);
    EXPECT_EQ(s.sceneItems, 0u);
    EXPECT_EQ(s.impostors.impostors, 0u);
    EXPECT_EQ(s.meshes.keyPoseInstances, 2u);
    EXPECT_EQ(s.meshes.keyPoseFills, 2u);
    EXPECT_GT(test::coveredPixels(image), 500u);
}

}  // namespace
}  // namespace throng
