// APP / matrices-and-bounds / CULL / DRAW: traversal order, update skipping, LOD selection, temporal
// coherence, and the draw list checked against an independent brute-force evaluation.

#include <gtest/gtest.h>

#include <map>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "throng/testkit/Cameras.h"
#include "throng/scenegraph/AppVisitor.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Geometry.h"
#include "throng/scenegraph/LOD.h"
#include "throng/scenegraph/RecordingBackend.h"
#include "throng/scenegraph/TraditionalProcessor.h"
#include "throng/scenegraph/Transform.h"
#include "throng/scenegraph/UpdateCallback.h"
#include "throng/testkit/RandomScenes.h"

using namespace throng;

namespace {

std::shared_ptr<Drawable> box(const std::string& name, double radius = 0.5, std::uint64_t prims = 12) {
    return std::make_shared<Drawable>(name, BoundingSphere(Vec3(0.0), radius), prims);
}

template <class T>
std::shared_ptr<T> named(const std::string& name) {
    auto n = std::make_shared<T>();
    n->setName(name);
    return n;
}

class RecordOrder : public UpdateCallback {
public:
    explicit RecordOrder(std::vector<std::string>& log) : log_(log) {}
    void update(Node& node, const FrameContext&) override { log_.push_back(node.name()); }

private:
    std::vector<std::string>& log_;
};

Camera lookingDownMinusZ(double far = 1000.0) {
    return testkit::lookingAt(Vec3(0.0), Vec3(0, 0, -1), {std::numbers::pi / 2, 1.0, 0.1, far});
}

}  // namespace

TEST(Traversal, AppRunsCallbacksDepthFirstParentsFirstAndSkipsSubtreesWithoutCallbacks) {
    std::vector<std::string> log;
    auto cb = std::make_shared<RecordOrder>(log);
    auto root = named<Group>("root");
    auto a = named<Group>("a"), c = named<Group>("c");
    auto b = named<Transform>("b");
    auto a1 = named<Group>("a1"), a2 = named<Group>("a2"), quiet = named<Group>("quiet");
    root->addChild(a);
    root->addChild(quiet);
    root->addChild(b);
    a->addChild(a1);
    a->addChild(a2);
    b->addChild(c);
    quiet->addChild(named<Group>("quietChild"));
    for (Node* n : {static_cast<Node*>(root.get()), static_cast<Node*>(a.get()), static_cast<Node*>(a1.get()),
                    static_cast<Node*>(a2.get()), static_cast<Node*>(b.get()), static_cast<Node*>(c.get())})
        n->setUpdateCallback(cb);
    EXPECT_EQ(root->appNodeCount(), 6u);
    EXPECT_EQ(quiet->appNodeCount(), 0u);

    AppVisitor app(FrameContext{});
    root->accept(app);
    EXPECT_EQ(log, (std::vector<std::string>{"root", "a", "a1", "a2", "b", "c"}));
    EXPECT_EQ(app.callbacksRun(), 6u);

    // Removing a subtree removes its callbacks from the ancestors' counts.
    root->removeChild(a.get());
    EXPECT_EQ(root->appNodeCount(), 3u);
    a1->setUpdateCallback(nullptr);
    EXPECT_EQ(a->appNodeCount(), 2u);
}

TEST(Traversal, TreeRulesAreEnforced) {
    auto root = named<Group>("root");
    auto child = named<Group>("child");
    root->addChild(child);
    EXPECT_THROW(root->addChild(nullptr), std::invalid_argument);
    auto other = named<Group>("other");
    try {
        other->addChild(child);
        FAIL() << "a node got two parents";
    } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("already has a parent ('root')"), std::string::npos) << e.what();
    }
    EXPECT_THROW(child->addChild(root), std::invalid_argument) << "cycle";
    EXPECT_THROW(root->child(5), std::out_of_range);
    EXPECT_EQ(child->parent(), root.get());
    EXPECT_TRUE(root->removeChild(child.get()));
    EXPECT_EQ(child->parent(), nullptr);
    EXPECT_FALSE(root->removeChild(child.get()));
}

TEST(Traversal, CullProducesDrawItemsInTraversalOrderWithWorldMatrices) {
    auto root = named<Group>("root");
    auto t1 = named<Transform>("t1"), t2 = named<Transform>("t2");
    TransformDofs d;
    d.translation = Vec3(-2, 0, -10);
    t1->setDofs(d);
    d.translation = Vec3(2, 0, -10);
    d.scale = Vec3(2.0);
    t2->setDofs(d);
    auto g1 = std::make_shared<Geometry>(box("first")), g2 = std::make_shared<Geometry>(box("second"));
    auto behind = std::make_shared<Geometry>(box("behind"));
    t1->addChild(g1);
    t2->addChild(g2);
    auto t3 = named<Transform>("t3");
    d = {};
    d.translation = Vec3(0, 0, 10);
    t3->setDofs(d);
    t3->addChild(behind);
    root->addChild(t1);
    root->addChild(t3);
    root->addChild(t2);

    TraditionalProcessor proc;
    RecordingBackend backend;
    proc.processFrame(*root, lookingDownMinusZ(), 0.0, &backend);
    ASSERT_EQ(backend.records().size(), 2u);
    EXPECT_EQ(backend.records()[0].node, g1.get());
    EXPECT_EQ(backend.records()[1].node, g2.get());
    EXPECT_EQ(backend.records()[1].worldMatrix[0][0], 2.0);
    EXPECT_EQ(Vec3(backend.records()[1].worldMatrix[3]), Vec3(2, 0, -10));
    EXPECT_EQ(backend.primitivesLastFrame(), 24u);
    EXPECT_EQ(proc.statistics().cull.drawItems, 2u);
    EXPECT_EQ(backend.frameCount(), 1u);
    // The world bound of t2 is its geometry's sphere scaled by 2.
    EXPECT_NEAR(t2->worldBound().radius(), 1.0, 1e-9);
}

TEST(Traversal, LodNodesSelectTheirChildByTheirOwnDistance) {
    auto root = named<Group>("root");
    auto place = named<Transform>("place");
    auto lod = named<LOD>("lod");
    auto hi = std::make_shared<Geometry>(box("hi")), mid = std::make_shared<Geometry>(box("mid")),
         lo = std::make_shared<Geometry>(box("lo"));
    lod->addChild(hi, 10.0);
    lod->addChild(mid, 50.0);
    lod->addChild(lo, 100.0);
    lod->setCenter(Vec3(0, 0, 0));
    place->addChild(lod);
    root->addChild(place);
    EXPECT_THROW(lod->addChild(std::make_shared<Geometry>(box("x")), 80.0), std::invalid_argument);
    EXPECT_EQ(lod->childCount(), 3u) << "a rejected child leaves the LOD unchanged";

    auto drawnAt = [&](double distance, double lodScale = 1.0) -> std::string {
        TransformDofs d;
        d.translation = Vec3(0, 0, -distance);
        place->setDofs(d);
        TraditionalProcessor proc;
        proc.setLodScale(lodScale);
        proc.processFrame(*root, lookingDownMinusZ(), 0.0);
        const auto& items = proc.drawList().items();
        return items.empty() ? "none" : items[0].drawable->name() + ":" + std::to_string(items[0].lodLevel);
    };
    EXPECT_EQ(drawnAt(5), "hi:0");
    EXPECT_EQ(drawnAt(10), "mid:1") << "a range's end belongs to the next child";
    EXPECT_EQ(drawnAt(49.9), "mid:1");
    EXPECT_EQ(drawnAt(75), "lo:2");
    EXPECT_EQ(drawnAt(150), "none");
    EXPECT_EQ(drawnAt(30, 2.0), "lo:2") << "LOD scale 2 doubles distances";
    EXPECT_EQ(lod->selectChild(9.99), 0);
    EXPECT_EQ(lod->selectChild(100.0), -1);
}

TEST(Traversal, UnchangedSubtreesAreNotRecomputedAndResultsMatchAFullRecompute) {
    std::mt19937_64 rng(3);
    auto scene = testkit::buildRandomScene(rng, {.objects = 50});
    const Camera cam = testkit::randomCamera(rng, 200.0);
    TraditionalProcessor proc;
    const auto first = proc.processFrame(*scene, cam, 0.0);
    EXPECT_GT(first.matrices.spheresRecomputed, 100u);
    const auto second = proc.processFrame(*scene, cam, 0.1);
    EXPECT_EQ(second.matrices.spheresRecomputed, 0u) << "nothing changed";
    EXPECT_EQ(second.matrices.worldMatricesComposed, 0u);
    EXPECT_EQ(second.cull.drawItems, first.cull.drawItems);

    // Move one object: only its subtree and its ancestors are recomputed.
    auto& object = static_cast<Transform&>(scene->child(7));
    TransformDofs d = object.dofs();
    d.translation += Vec3(1, 2, 3);
    if (object.usesDofs()) object.setDofs(d);
    else object.setMatrix(glm::translate(object.localMatrix(), Vec3(1, 2, 3)));
    const auto third = proc.processFrame(*scene, cam, 0.2);
    EXPECT_GT(third.matrices.spheresRecomputed, 1u);
    EXPECT_LT(third.matrices.spheresRecomputed, first.matrices.spheresRecomputed / 10);

    // A processor recomputing everything reaches the same bounds and draw list.
    std::vector<BoundingSphere> incremental;
    for (const auto& c : scene->children()) incremental.push_back(c->worldBound());
    const auto listed = proc.drawList().items();
    const std::vector<DrawItem> incrementalItems(listed.begin(), listed.end());
    TraditionalProcessor full;
    full.setFullRecompute(true);
    full.processFrame(*scene, cam, 0.3);
    for (std::size_t i = 0; i < scene->childCount(); ++i) EXPECT_EQ(scene->child(i).worldBound(), incremental[i]);
    ASSERT_EQ(full.drawList().size(), incrementalItems.size());
    std::size_t i = 0;
    for (const DrawItem& item : full.drawList().items()) EXPECT_EQ(item.node, incrementalItems[i++].node);
}

namespace {

// Brute force: world matrices by full 4x4 products, LOD choice by each LOD's own distance, and a
// leaf drawn iff its own sphere is not outside (a sphere holding a visible one is never outside,
// so ancestors cannot change the answer).
void bruteForce(const Node& node, const Mat4& world, const Camera& cam, const Frustum& f,
                std::vector<const Node*>& drawn) {
    if (auto* g = dynamic_cast<const Geometry*>(&node)) {
        const BoundingSphere s = g->drawable().localBound().transformed(world);
        if (f.classify(s) != Containment::Outside) drawn.push_back(g);
        return;
    }
    Mat4 w = world;
    if (auto* t = dynamic_cast<const Transform*>(&node)) w = world * t->localMatrix();
    if (auto* lod = dynamic_cast<const LOD*>(&node)) {
        const Vec3 c = Vec3(w * Vec4(lod->center(), 1.0));
        const int i = lod->selectChild(glm::length(c - cam.eye()));
        if (i >= 0) bruteForce(lod->child(static_cast<std::size_t>(i)), w, cam, f, drawn);
        return;
    }
    if (auto* g = dynamic_cast<const Group*>(&node))
        for (const auto& c : g->children()) bruteForce(*c, w, cam, f, drawn);
}

}  // namespace

TEST(Traversal, DrawListMatchesBruteForceOnRandomScenes) {
    std::mt19937_64 rng(99);
    std::size_t totalDrawn = 0, totalRejected = 0;
    for (int scene = 0; scene < 60; ++scene) {
        auto root = testkit::buildRandomScene(rng, {.objects = 60, .extent = 150.0});
        TraditionalProcessor proc;
        for (int view = 0; view < 5; ++view) {
            const Camera cam = testkit::randomCamera(rng, 150.0);
            proc.processFrame(*root, cam, view * 0.1);
            std::vector<const Node*> expected;
            bruteForce(*root, Mat4(1.0), cam, cam.frustum(), expected);
            std::vector<const Node*> got;
            for (const DrawItem& item : proc.drawList().items()) got.push_back(item.node);
            ASSERT_EQ(got, expected) << "scene " << scene << " view " << view;
            totalDrawn += got.size();
            totalRejected += proc.statistics().cull.nodesRejected;
        }
    }
    EXPECT_GT(totalDrawn, 1000u);
    EXPECT_GT(totalRejected, 1000u);
}

TEST(Traversal, SmallerCullingFrustumDrawsASubset) {
    std::mt19937_64 rng(17);
    auto root = testkit::buildRandomScene(rng, {.objects = 200});
    Camera cam;
    cam.setPerspective(1.2, 1.5, 0.1, 2000);
    cam.setLookAt(Vec3(0, 0, 400), Vec3(0.0), Vec3(0, 1, 0));
    TraditionalProcessor proc;
    proc.processFrame(*root, cam, 0.0);
    const std::size_t all = proc.drawList().size();
    Camera narrow = cam;
    narrow.setPerspective(0.4, 1.5, 0.1, 2000);
    proc.setCullingFrustum(narrow.frustum());
    proc.processFrame(*root, cam, 0.0);
    EXPECT_LT(proc.drawList().size(), all);
    EXPECT_GT(proc.drawList().size(), 0u);
}
