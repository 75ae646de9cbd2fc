// Faces (seed 002 §7.1): expressions, blinks and phrases over a base behaviour, each under
// behavioural LOD and only where declared.
//
//   * An actor that leaves the face band and comes back shows exactly the expression, the blink
//     and the mouth it would show had it been evaluated throughout (bit for bit), and so does one
//     evaluated for the first time at the end.
//   * Expressions blend smoothly, blinks are half sines (never a step), at the declared rate;
//     the far face band keeps the strongest weight only.
//   * In a group at most one member speaks at a time, and every member has its turns.
//   * A simulation whose scene declares none of the three makes no face layer and counts no tick;
//     one that declares them counts them.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "throng/actors/ActorProcessor.h"
#include "throng/actors/ActorTemplate.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/sim/FaceLayer.h"
#include "throng/sim/SceneParser.h"
#include "throng/sim/Simulation.h"
#include "throng/testkit/Assets.h"

using namespace throng;
using namespace throng::sim;

namespace {

// A head: one node with a turning DOF, its mesh with the targets Angry, Happy, Blink and MouthOpen.
std::shared_ptr<const ActorTemplate> head() {
    auto mesh = std::make_shared<MeshData>();
    mesh->name = "head";
    mesh->positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    mesh->indices = {0, 1, 2};
    for (const char* name : {"Angry", "Happy", "Blink", "MouthOpen"})
        mesh->morphTargets.push_back(MorphTarget{name, std::vector<glm::vec3>(3, glm::vec3(0, 0, 0.01f)), {}, 0.0f});
    ActorTemplateBuilder b("head");
    SkeletonNode n;
    n.name = "neck";
    n.dofs = {Dof::rotation(glm::vec3(0, 1, 0), -1.0f, 1.0f)};
    n.geometry.addLevel(std::numeric_limits<double>::infinity(), std::make_shared<MeshDrawable>(mesh));
    b.addNode(n);
    ClipChannel c;
    c.node = 0;
    c.times = {0.0f, 1.0f};
    c.values = {0.0f, 0.5f};
    b.addClip(std::make_shared<const AnimationClip>("turn", std::vector<ClipChannel>{c}));
    return b.build();
}

FaceLayer::Settings allThree() {
    FaceLayer::Settings s;
    s.face = s.blink = s.phrase = true;
    s.faceLevels = {10.0, 20.0};
    s.blinkLevels = {10.0};
    s.phraseLevels = {10.0, 20.0};
    s.expressions = {{"calm", {}, 2.0}, {"cross", {{"Angry", 1.0f}}, 1.5}, {"glad", {{"Happy", 0.8f}, {"Angry", 0.2f}}, 1.0}};
    s.transition = 0.5;
    s.blinkMean = 2.0;
    s.blinkSpread = 1.0;
    s.phrases = {"Hello there", "Lovely day"};
    s.seed = 11;
    return s;
}

struct Faces {
    std::shared_ptr<const ActorTemplate> tmpl = head();
    std::shared_ptr<KeyframeBehaviour> base = std::make_shared<KeyframeBehaviour>();
    EffectCounters counters;
    std::shared_ptr<FaceLayer> layer;
    explicit Faces(const FaceLayer::Settings& s = allThree()) { layer = std::make_shared<FaceLayer>(base, s, &counters); }
    // An actor of stream `stream`, member `member` of a group of `size`.
    std::uint32_t add(std::uint64_t stream, std::uint64_t group = 0, std::uint32_t member = 0, std::uint32_t size = 1) {
        KeyframeBehaviour::Actor a;
        a.tmpl = tmpl;
        return layer->wrap(base->addActor(a), tmpl, stream, group, member, size);
    }
    // The DOF values of `slot` posed at `time` seen from `distance`.
    std::vector<float> pose(std::uint32_t slot, double time, double distance) {
        std::vector<float> dofs(tmpl->restDofs().begin(), tmpl->restDofs().end());
        layer->pose(slot, time, layer->levelFor(distance), *tmpl, {}, dofs, nullptr);
        return dofs;
    }
};

}  // namespace

TEST(FaceLayer, AnActorBackInTheBandShowsExactlyWhatItWouldHaveShown) {
    Faces f;
    const std::uint32_t always = f.add(7, 3, 1, 3), away = f.add(7, 3, 1, 3), late = f.add(7, 3, 1, 3);
    int compared = 0, moving = 0;
    std::vector<float> previous;
    for (int frame = 0; frame <= 30 * 60; ++frame) {
        const double t = frame / 30.0;
        const bool out = t >= 9.0 && t < 41.0;  // 32 s beyond every band
        const std::vector<float> a = f.pose(always, t, 2.0);
        const std::vector<float> b = f.pose(away, t, out ? 50.0 : 2.0);
        if (out) {
            EXPECT_EQ(std::vector<float>(b.begin() + f.tmpl->morphWeightOffset(), b.end()), std::vector<float>(4, 0.0f))
                << "beyond the bands the face stays neutral";
            continue;
        }
        EXPECT_EQ(a, b) << "at " << t << " s";
        ++compared;
        if (!previous.empty() && previous != a) ++moving;
        previous = a;
    }
    EXPECT_GT(compared, 30 * 20);
    EXPECT_GT(moving, 30 * 5) << "the face hardly moves: the comparison proves little";
    // Evaluated for the first time at the end: the same (walked from the start).
    EXPECT_EQ(f.pose(late, 60.0, 2.0), f.pose(always, 60.0, 2.0));
    // The blink phase and the speech too.
    EXPECT_EQ(f.layer->blinkAt(away, 61.3), f.layer->blinkAt(always, 61.3));
    EXPECT_EQ(f.layer->speechAt(away, 61.3).progress, f.layer->speechAt(always, 61.3).progress);
    // Ticks: one per effect per evaluation within its band, none beyond.
    f.layer->flushCounts();
    const std::uint64_t faceTicks = f.counters.of("face").ticks;
    EXPECT_GT(faceTicks, 0u);
    EXPECT_LT(faceTicks, 3u * 30 * 60 + 3) << "the actor out of its band was evaluated";
    EXPECT_EQ(f.counters.of("face").constructed, 1u);
    EXPECT_EQ(f.counters.of("blink").constructed, 1u);
    EXPECT_EQ(f.counters.of("phrase").constructed, 1u);
}

// The crowd keeps an actor's DOF values from frame to frame: the face of one frame does not carry
// into the next (posing twice at one time gives one pose), nor beyond the bands (neutral again).
TEST(FaceLayer, AFaceDoesNotCarryOverInTheValuesAnActorKeeps) {
    Faces f;
    const std::uint32_t slot = f.add(5, 1, 0, 1);
    std::vector<float> kept(f.tmpl->restDofs().begin(), f.tmpl->restDofs().end());
    const auto morph = [&] { return std::vector<float>(kept.begin() + f.tmpl->morphWeightOffset(), kept.end()); };
    int moved = 0;
    for (int i = 0; i < 600; ++i) {
        const double t = 0.1 * i;
        f.layer->pose(slot, t, f.layer->levelFor(2.0), *f.tmpl, {}, kept, nullptr);
        const std::vector<float> once = kept;
        f.layer->pose(slot, t, f.layer->levelFor(2.0), *f.tmpl, {}, kept, nullptr);
        EXPECT_EQ(kept, once) << "at " << t << " s";
        moved += morph() != std::vector<float>(4, 0.0f);
    }
    EXPECT_GT(moved, 100);
    f.layer->pose(slot, 61.0, f.layer->levelFor(500.0), *f.tmpl, {}, kept, nullptr);
    EXPECT_EQ(morph(), std::vector<float>(4, 0.0f)) << "beyond the bands the face is neutral again";
}

TEST(FaceLayer, ExpressionsBlendAndBlinksNeverStep) {
    Faces f;
    const std::uint32_t slot = f.add(21);
    const double dt = 1.0 / 240.0;
    double largestWeightStep = 0.0, largestBlinkStep = 0.0, lastBlink = 0.0;
    std::vector<float> last = f.layer->expressionAt(slot, 0.0);
    int blinks = 0;
    bool closed = false;
    for (int i = 1; i < int(600.0 / dt); ++i) {
        const double t = i * dt;
        const std::vector<float> now = f.layer->expressionAt(slot, t);
        for (std::size_t c = 0; c < now.size(); ++c) largestWeightStep = std::max(largestWeightStep, double(std::abs(now[c] - last[c])));
        last = now;
        const double b = f.layer->blinkAt(slot, t);
        ASSERT_GE(b, 0.0);
        ASSERT_LE(b, 1.0);
        largestBlinkStep = std::max(largestBlinkStep, std::abs(b - lastBlink));
        lastBlink = b;
        if (b > 0.9 && !closed) ++blinks;
        closed = b > 0.9 ? true : b < 0.1 ? false : closed;
    }
    // Smoothstep over 0.5 s: the steepest slope is 1.5 per transition (weight 1), 3 per second.
    EXPECT_LT(largestWeightStep, 3.0 * dt * 1.05);
    EXPECT_GT(largestWeightStep, 0.0);
    // Half a sine over 0.15 s: slope at most pi / 0.15 per second.
    EXPECT_LT(largestBlinkStep, std::numbers::pi / 0.15 * dt * 1.05);
    // Mean interval 2 s over 600 s: about 300 blinks.
    EXPECT_GT(blinks, 250);
    EXPECT_LT(blinks, 350);
    // The far face band keeps the strongest weight only.
    int strongestOnly = 0;
    for (int i = 0; i < 200; ++i) {
        const std::vector<float> far = f.pose(slot, 0.37 * i, 15.0);
        int nonZero = 0;  // of the expressions' channels (the mouth still moves in this band)
        for (const char* name : {"Angry", "Happy"})
            nonZero += far[f.tmpl->morphWeightOffset() + std::size_t(f.tmpl->findMorphChannel(name))] != 0.0f;
        EXPECT_LE(nonZero, 1);
        strongestOnly += nonZero == 1;
    }
    EXPECT_GT(strongestOnly, 50);
}

TEST(FaceLayer, GroupMembersTakeTurnsAndMouthsMoveOnlyWhenSpeaking) {
    Faces f;
    std::vector<std::uint32_t> group;
    for (std::uint32_t k = 0; k < 4; ++k) group.push_back(f.add(100 + k, 9, k, 4));
    std::vector<int> spoke(4, 0);
    const int mouth = f.tmpl->findMorphChannel("MouthOpen");
    ASSERT_GE(mouth, 0);
    for (int i = 0; i < 120 * 30; ++i) {
        const double t = i / 30.0;
        int speaking = 0;
        for (std::uint32_t k = 0; k < 4; ++k) {
            const FaceLayer::Speech s = f.layer->speechAt(group[k], t);
            const float open = f.pose(group[k], t, 2.0)[f.tmpl->morphWeightOffset() + std::size_t(mouth)];
            if (s.phrase < 0) {
                EXPECT_EQ(open, 0.0f) << "a silent mouth moves";
                continue;
            }
            ++speaking;
            ++spoke[k];
            EXPECT_GE(s.progress, 0.0);
            EXPECT_LE(s.progress, 1.0);
        }
        EXPECT_LE(speaking, 1) << "two members speak at once at " << t << " s";
    }
    for (int k = 0; k < 4; ++k) EXPECT_GT(spoke[k], 0) << "member " << k << " never speaks";
}

// A character without an eyelid target blinks with its eye joints' scale DOFs: squashed to a tenth
// in y at the middle of a blink, untouched between blinks.
TEST(FaceLayer, WithoutAnEyelidTargetEyeJointsWithAScaleBlink) {
    auto mesh = std::make_shared<MeshData>();
    mesh->name = "eye";
    mesh->positions = {{0, 0, 0}, {0.01f, 0, 0}, {0, 0.01f, 0}};
    mesh->indices = {0, 1, 2};
    ActorTemplateBuilder b("eyes");
    SkeletonNode head;
    head.name = "head";
    head.dofs = {Dof::rotation(glm::vec3(0, 1, 0), -1.0f, 1.0f)};
    b.addNode(head);
    SkeletonNode eye;
    eye.name = "LeftEye";
    eye.parent = 0;
    eye.dofs = {Dof{DofKind::Scale, glm::vec3(0), -INFINITY, INFINITY, {1, 1, 1, 0}}};
    eye.geometry.addLevel(std::numeric_limits<double>::infinity(), std::make_shared<MeshDrawable>(mesh));
    b.addNode(eye);
    ClipChannel c;
    c.times = {0.0f};
    c.values = {0.0f};
    b.addClip(std::make_shared<const AnimationClip>("still", std::vector<ClipChannel>{c}));
    const auto tmpl = b.build();
    FaceLayer::Settings s;
    s.blink = true;
    s.blinkMean = 1.0;
    s.blinkSpread = 0.5;
    auto base = std::make_shared<KeyframeBehaviour>();
    FaceLayer layer(base, s);
    ASSERT_EQ(layer.rigOf(*tmpl).eyeJoints, std::vector<int>{1});
    KeyframeBehaviour::Actor a;
    a.tmpl = tmpl;
    const std::uint32_t slot = layer.wrap(base->addActor(a), tmpl, 3, 0, 0, 1);
    const std::uint32_t yScale = tmpl->dofValueOffset(1, 0) + 1;
    double least = 1.0;
    for (int i = 0; i < 3000; ++i) {
        const double t = i / 300.0;
        std::vector<float> dofs(tmpl->restDofs().begin(), tmpl->restDofs().end());
        layer.pose(slot, t, layer.levelFor(2.0), *tmpl, {}, dofs, nullptr);
        const double w = layer.blinkAt(slot, t);
        EXPECT_NEAR(dofs[yScale], 1.0 - 0.9 * w, 1e-6) << "at " << t << " s";
        EXPECT_EQ(dofs[yScale - 1], 1.0f) << "only y is squashed";
        least = std::min(least, double(dofs[yScale]));
    }
    EXPECT_LT(least, 0.15) << "no blink closed the eyes";
}

TEST(FaceLayer, BadSettingsAreNamed) {
    auto base = std::make_shared<KeyframeBehaviour>();
    const auto fails = [&](FaceLayer::Settings s, const std::string& what) {
        try {
            FaceLayer layer(base, s);
        } catch (const std::invalid_argument& e) {
            return std::string(e.what()).find(what) != std::string::npos ? std::string() : std::string(e.what());
        }
        return std::string("(accepted)");
    };
    FaceLayer::Settings s = allThree();
    s.faceLevels = {10.0, 5.0};
    EXPECT_EQ(fails(s, "face level ends"), "");
    s = allThree();
    s.blinkSpread = 3.0;
    EXPECT_EQ(fails(s, "blink spread"), "");
    s = allThree();
    s.expressions[1].weights["Angry"] = NAN;
    EXPECT_EQ(fails(s, "expression 'cross'"), "");
    s = allThree();
    s.lettersPerSecond = 0.0;
    EXPECT_EQ(fails(s, "letters per second"), "");
}

TEST(FaceLayer, UndeclaredFacesAreNeverMadeNorTicked) {
    const std::string base = R"({
      "seed": 3,
      "town": {"blocksX": 2, "blocksZ": 2, "blockTiles": 3, "tileSize": 8, "seed": 5, "tiles": "town/kenney_city_builder"},
      "templates": {"robot": {"gltf": "characters/RobotExpressive.glb", "walkClip": "Walking", "idleClip": "Idle"}},
      "actors": [{"template": "robot", "count": 12, "behaviour": "walk"}, {"template": "robot", "count": 6, "behaviour": "idle"}],
      "camera": {"path": [{"time": 0, "eye": [0, 6, 10], "target": [0, 0, 0]}]})";
    for (const bool declared : {false, true}) {
        SCOPED_TRACE(declared ? "declared" : "not declared");
        auto world = Simulation::build(
            parseScene(base + (declared ? R"(, "effects": {"face": true, "blink": true, "phrase": {"levels": [400]}}})" : "}"),
                       testkit::sharedAssets()));
        ActorProcessor processor(world->crowd());
        for (int f = 0; f < 20; ++f) {
            const double t = world->step().time;
            processor.processFrame(world->root(), world->camera().at(t, 1.0), t);
        }
        for (const auto& layer : world->faceLayers()) layer->flushCounts();
        EXPECT_EQ(world->faceLayers().size(), declared ? 2u : 0u);
        for (const char* effect : {"face", "blink", "phrase"}) {
            EXPECT_EQ(world->effects().of(effect).constructed, declared ? 2u : 0u) << effect;
            if (!declared) {
                EXPECT_EQ(world->effects().of(effect).ticks, 0u) << effect;
            }
        }
        // The robot has expressions but no eyelid and no mouth: only the face ticks.
        if (declared) {
            EXPECT_GT(world->effects().of("face").ticks, 0u);
        }
    }
}
