#include "OsgCrowd.h"

#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

#include <glm/gtc/type_ptr.hpp>
#include <osg/FrameStamp>
#include <osg/Geode>
#include <osg/Geometry>
#include <osg/LOD>
#include <osg/MatrixTransform>
#include <osg/NodeCallback>
#include <osgUtil/CullVisitor>
#include <osgUtil/SceneView>
#include <osgUtil/StateGraph>

#include "throng/actors/Actor.h"
#include "throng/actors/ActorGroup.h"
#include "throng/actors/Crowd.h"
#include "throng/actors/KeyframeBehaviour.h"
#include "throng/actors/SkeletonPose.h"
#include "throng/scenegraph/Camera.h"
#include "throng/scenegraph/Group.h"
#include "throng/scenegraph/MeshDrawable.h"
#include "throng/scenegraph/Stopwatch.h"

namespace throng::peers {
namespace {

osg::Matrixd toOsg(const Mat4& m) { return osg::Matrixd(glm::value_ptr(m)); }

// A geometry leaf shared by every clone of a template (OSG's instancing: one Geode, many parents).
// Given a sphere, it is its bound, so OSG culls the leaf by the sphere Throng culls it by (a Geode
// otherwise bounds the box of its drawables).
class SharedGeode : public osg::Geode {
public:
    explicit SharedGeode(std::optional<osg::BoundingSphere> sphere) : sphere_(sphere) {}
    osg::BoundingSphere computeBound() const override { return sphere_ ? *sphere_ : osg::Geode::computeBound(); }
    // Empties the parent list before the scene is taken apart: every parent would otherwise look
    // itself up in a list of 10^5 entries (quadratic teardown). The parents are released next.
    void forgetParents() { _parents.clear(); }

private:
    std::optional<osg::BoundingSphere> sphere_;
};

// The OSG copy of one VaLod: its levels with a drawable become children with [previous end, end)
// ranges. It remembers which Skeleton node (part) and vaLod level each child stands for.
class PartLod : public osg::LOD {
public:
    explicit PartLod(std::uint32_t part) : part_(part) {}
    // Part number as in Throng's draw items.
    std::uint32_t part() const { return part_; }
    // vaLod level shown by child `child`.
    std::uint32_t levelOf(unsigned child) const { return levels_[child]; }
    // Adds `geode` shown from `from` to `to` metres as vaLod level `level`.
    void addLevel(osg::Node* geode, float from, float to, std::uint32_t level) {
        addChild(geode, from, to);
        levels_.push_back(level);
    }

private:
    std::uint32_t part_;
    std::vector<std::uint32_t> levels_;
};

// What the OSG copies of one template share: the geometry leaves and scratch space for posing.
struct TemplateMirror {
    const ActorTemplate* tmpl = nullptr;
    std::vector<std::vector<osg::ref_ptr<SharedGeode>>> nodeGeodes;  // per node, per level (null: nothing shown)
    std::vector<osg::ref_ptr<SharedGeode>> rootGeodes;                // per level of the actor-level vaLod
    std::vector<float> dofs;                                          // one actor's DOF values, while it is updated
    std::vector<Affine> model;                                        // its nodes' transforms to the Skeleton Root
};

// The Reference Point transform of one actor, carrying what its update callback needs.
class ActorTransform : public osg::MatrixTransform {
public:
    ActorId id = 0;
    Behaviour* behaviour = nullptr;
    std::uint32_t slot = 0;
    TemplateMirror* mirror = nullptr;
    osg::MatrixTransform* skeletonRoot = nullptr;
    std::vector<osg::MatrixTransform*> joints;  // per Skeleton node
    std::vector<osg::LOD*> lods;                // per Skeleton node with geometry whose centre follows the root, else null
};

// Sets every matrix of an actor at the frame's simulation time, as Throng's traditional APP does:
// the Reference Point, the Skeleton Root and every DOF at the behaviour's full precision (level 0).
// Each LOD's centre is moved to the Skeleton Root, in its node's frame.
class ActorUpdate : public osg::NodeCallback {
public:
    void operator()(osg::Node* node, osg::NodeVisitor* nv) override {
        auto& actor = static_cast<ActorTransform&>(*node);
        const osg::FrameStamp& stamp = *nv->getFrameStamp();
        const double time = stamp.getSimulationTime();
        const FrameContext context{time, 0.0, stamp.getFrameNumber(), nullptr};
        Behaviour& b = *actor.behaviour;
        actor.setMatrix(toOsg(b.referencePoint(actor.slot, context, nullptr)));
        actor.skeletonRoot->setMatrix(toOsg(rootPoseMatrix(b.skeletonRoot(actor.slot, time, 0, nullptr))));
        TemplateMirror& m = *actor.mirror;
        const ActorTemplate& t = *m.tmpl;
        // DOFs no channel drives keep their rest value, as in the actor's own state in the Crowd.
        std::copy(t.restDofs().begin(), t.restDofs().end(), m.dofs.begin());
        b.pose(actor.slot, time, 0, t, {}, m.dofs, nullptr);
        const auto nodes = t.nodes();
        for (std::size_t i = 0; i < nodes.size(); ++i) {
            const Affine local = nodeLocalTransform(nodes[i], m.dofs.data() + t.dofOffset(i));
            actor.joints[i]->setMatrix(toOsg(local.toDMat4()));
            const int p = nodes[i].parent;
            m.model[i] = p < 0 ? local : m.model[static_cast<std::size_t>(p)] * local;
            if (osg::LOD* lod = actor.lods[i]) {
                // The Skeleton Root's origin in node i's frame (rigid: the inverse is the transpose).
                const glm::vec3 c = -(glm::transpose(m.model[i].linear) * m.model[i].translation);
                lod->setCenter(osg::Vec3(c.x, c.y, c.z));
            }
        }
        traverse(node, nv);
    }
};

// A CullVisitor that records, for every drawable reaching the render bins, the actor, part and
// level it belongs to. Only for the visibility check: it costs a path search per drawable.
class RecordingCullVisitor : public osgUtil::CullVisitor {
public:
    using osgUtil::CullVisitor::apply;
    explicit RecordingCullVisitor(std::vector<VisiblePart>& out) : out_(out) {}

    void apply(osg::Drawable& drawable) override {
        osgUtil::StateGraph* graph = getCurrentStateGraph();
        const std::size_t before = graph->_leaves.size();
        osgUtil::CullVisitor::apply(drawable);
        if (getCurrentStateGraph() != graph || graph->_leaves.size() == before) return;  // not binned
        const osg::NodePath& path = getNodePath();
        const PartLod* lod = nullptr;
        std::size_t k = path.size();
        while (k-- > 1 && !(lod = dynamic_cast<const PartLod*>(path[k - 1]))) {}
        if (!lod) throw std::logic_error("RecordingCullVisitor: a drawable outside any part LOD was binned");
        const unsigned child = lod->getChildIndex(path[k]);
        const ActorTransform* actor = nullptr;
        for (std::size_t j = k - 1; j-- > 0 && !actor;) actor = dynamic_cast<const ActorTransform*>(path[j]);
        if (!actor) throw std::logic_error("RecordingCullVisitor: a drawable outside any actor was binned");
        out_.push_back({actor->id, lod->part(), lod->levelOf(child)});
    }

private:
    std::vector<VisiblePart>& out_;
};

// A SceneView set to cull as Throng does, without a GL context.
osg::ref_ptr<osgUtil::SceneView> makeSceneView(osg::Node* scene, osg::FrameStamp* stamp, bool matchThrong) {
    osg::ref_ptr<osgUtil::SceneView> view = new osgUtil::SceneView;
    view->setDefaults(0);  // no headlight, nothing compiled for GL
    view->setSceneData(scene);
    view->setFrameStamp(stamp);
    view->setViewport(0, 0, 1280, 720);
    if (!matchThrong) return view;
    // Throng culls against all six planes and never moves them: OSG by default culls the four
    // sides only and computes near/far from what it finds.
    view->setComputeNearFarMode(osg::CullSettings::DO_NOT_COMPUTE_NEAR_FAR);
    // Throng has no small-feature culling (OSG's default drops what covers < 2 pixels).
    view->setCullingMode(osg::CullSettings::VIEW_FRUSTUM_CULLING);
    return view;
}

std::string actorName(ActorId id) { return "actor " + std::to_string(id); }

}  // namespace

struct OsgCrowd::Impl {
    const Crowd* crowd = nullptr;
    OsgCrowdOptions options;
    osg::ref_ptr<osg::Group> root;
    osg::ref_ptr<osg::FrameStamp> stamp = new osg::FrameStamp;
    osg::ref_ptr<osgUtil::SceneView> view, recordingView;
    std::vector<VisiblePart> recorded;
    osg::ref_ptr<ActorUpdate> update = new ActorUpdate;
    std::map<const ActorTemplate*, std::unique_ptr<TemplateMirror>> templates;
    std::size_t nodes = 0;
    unsigned frameNumber = 0;

    TemplateMirror& mirrorOf(const ActorTemplate& t, ActorId id);
    osg::ref_ptr<ActorTransform> makeActor(ActorId id);
};

TemplateMirror& OsgCrowd::Impl::mirrorOf(const ActorTemplate& t, ActorId id) {
    auto found = templates.find(&t);
    if (found != templates.end()) return *found->second;
    const std::string where = "OsgCrowd: " + actorName(id) + " (template '" + t.name() + "')";
    auto m = std::make_unique<TemplateMirror>();
    m->tmpl = &t;
    m->dofs.assign(t.restDofs().begin(), t.restDofs().end());
    m->model.resize(t.nodeCount());
    // One shared leaf per level showing something; its sphere is the drawable's, in the node frame.
    auto leaves = [&](const VaLod& lod, const std::string& part) {
        std::vector<osg::ref_ptr<SharedGeode>> out;
        for (const VaLodLevel& level : lod.levels()) {
            if (level.skin >= 0) throw std::invalid_argument(where + ": " + part + " has a skinned level (not mirrored)");
            if (!level.drawable) {
                out.emplace_back();
                continue;
            }
            const BoundingSphere& s = level.drawable->localBound();
            const osg::Vec3 c(float(s.center().x), float(s.center().y), float(s.center().z));
            const auto* mesh = dynamic_cast<const MeshDrawable*>(level.drawable.get());
            osg::ref_ptr<SharedGeode> geode = new SharedGeode(
                options.matchThrong ? std::optional<osg::BoundingSphere>(osg::BoundingSphere(c, float(s.radius()))) : std::nullopt);
            osg::ref_ptr<osg::Geometry> geometry = new osg::Geometry;
            if (mesh) {
                // The same triangles (nothing draws them; they make the copy an honest scene).
                osg::ref_ptr<osg::Vec3Array> vertices = new osg::Vec3Array;
                for (const glm::vec3& p : mesh->mesh().positions) vertices->push_back(osg::Vec3(p.x, p.y, p.z));
                geometry->setVertexArray(vertices);
                const auto& indices = mesh->mesh().indices;
                geometry->addPrimitiveSet(new osg::DrawElementsUInt(GL_TRIANGLES, indices.begin(), indices.end()));
            }
            // A box around the sphere: the drawable's own box test then passes whenever the leaf's
            // sphere test did, so the sphere decides, as in Throng. (OSG as it comes bounds the
            // vertices with a box, and culls by it.)
            if (options.matchThrong || !mesh) {
                const float r = float(s.radius()) * (1.0f + 1e-5f) + 1e-6f;
                geometry->setInitialBound(osg::BoundingBox(c - osg::Vec3(r, r, r), c + osg::Vec3(r, r, r)));
            }
            geode->addDrawable(geometry);
            nodes += 2;
            out.push_back(geode);
        }
        return out;
    };
    for (const SkeletonNode& n : t.nodes()) {
        if (n.restScale != glm::vec3(1.0f))
            throw std::invalid_argument(where + ": Skeleton node '" + n.name + "' is scaled (OSG LODs measure distances in the node's frame)");
        for (const Dof& d : n.dofs)
            if (d.kind == DofKind::Scale)
                throw std::invalid_argument(where + ": Skeleton node '" + n.name + "' has a scale DOF (OSG LODs measure distances in the node's frame)");
        m->nodeGeodes.push_back(leaves(n.geometry, "Skeleton node '" + n.name + "'"));
    }
    m->rootGeodes = leaves(t.rootGeometry(), "the actor-level geometry");
    return *templates.emplace(&t, std::move(m)).first->second;
}

osg::ref_ptr<ActorTransform> OsgCrowd::Impl::makeActor(ActorId id) {
    const Crowd::State& s = crowd->state();
    const ActorTemplate& t = *s.tmpl[id];
    if (!dynamic_cast<const KeyframeBehaviour*>(s.behaviour[id]))
        throw std::invalid_argument("OsgCrowd: " + actorName(id) +
                                    " is not driven by a KeyframeBehaviour (the OSG copy plays closed-form motion only)");
    if (s.held[id] >= 0) throw std::invalid_argument("OsgCrowd: " + actorName(id) + " holds an object (not mirrored)");
    TemplateMirror& m = mirrorOf(t, id);

    osg::ref_ptr<ActorTransform> actor = new ActorTransform;
    actor->id = id;
    actor->behaviour = s.behaviour[id];
    actor->slot = s.slot[id];
    actor->mirror = &m;
    actor->setUpdateCallback(update);
    osg::ref_ptr<osg::MatrixTransform> skeletonRoot = new osg::MatrixTransform;
    actor->skeletonRoot = skeletonRoot.get();
    actor->addChild(skeletonRoot);
    nodes += 2;

    // An LOD for a vaLod: a child per level that shows something, over [previous end, end).
    auto makeLod = [&](const VaLod& valod, const std::vector<osg::ref_ptr<SharedGeode>>& geodes, std::uint32_t part) {
        osg::ref_ptr<PartLod> lod = new PartLod(part);
        if (options.matchThrong) lod->setCenter(osg::Vec3(0, 0, 0));  // user-defined centre, moved by the update
        float from = 0.0f;
        for (std::size_t k = 0; k < valod.levels().size(); ++k) {
            const auto to = static_cast<float>(valod.levels()[k].maxDistance);
            if (geodes[k]) lod->addLevel(geodes[k].get(), from, to, static_cast<std::uint32_t>(k));
            from = to;
        }
        ++nodes;
        return lod;
    };
    // The actor-level geometry hangs in the Skeleton Root frame, where the root is the origin.
    if (!t.rootGeometry().empty())
        skeletonRoot->addChild(makeLod(t.rootGeometry(), m.rootGeodes, static_cast<std::uint32_t>(t.nodeCount())));
    const auto nodesOfT = t.nodes();
    actor->joints.resize(nodesOfT.size());
    actor->lods.assign(nodesOfT.size(), nullptr);
    for (std::size_t i = 0; i < nodesOfT.size(); ++i) {
        osg::ref_ptr<osg::MatrixTransform> joint = new osg::MatrixTransform;
        ++nodes;
        actor->joints[i] = joint.get();
        if (!nodesOfT[i].geometry.empty()) {
            osg::ref_ptr<PartLod> lod = makeLod(nodesOfT[i].geometry, m.nodeGeodes[i], static_cast<std::uint32_t>(i));
            if (options.matchThrong) actor->lods[i] = lod.get();
            joint->addChild(lod);
        }
        const int p = nodesOfT[i].parent;  // parents come first (depth-first order)
        (p < 0 ? skeletonRoot.get() : actor->joints[static_cast<std::size_t>(p)])->addChild(joint);
    }
    return actor;
}

OsgCrowd::OsgCrowd(const Crowd& crowd, const Group& root, const OsgCrowdOptions& options) : impl_(std::make_unique<Impl>()) {
    Impl& im = *impl_;
    im.crowd = &crowd;
    im.options = options;
    im.root = new osg::Group;
    ++im.nodes;
    // The same grouping as the Throng scene: an osg::Group per ActorGroup, actors under it.
    for (std::size_t c = 0; c < root.childCount(); ++c) {
        const Node& child = root.child(c);
        if (const auto* group = dynamic_cast<const ActorGroup*>(&child)) {
            if (&group->crowd() != &crowd) throw std::invalid_argument("OsgCrowd: child " + std::to_string(c) + " of the root holds actors of another crowd");
            osg::ref_ptr<osg::Group> g = new osg::Group;
            ++im.nodes;
            for (ActorId id : group->ids()) g->addChild(im.makeActor(id));
            im.root->addChild(g);
        } else if (const auto* actor = dynamic_cast<const Actor*>(&child)) {
            if (&actor->crowd() != &crowd) throw std::invalid_argument("OsgCrowd: child " + std::to_string(c) + " of the root holds an actor of another crowd");
            im.root->addChild(im.makeActor(actor->id()));
        } else {
            throw std::invalid_argument("OsgCrowd: child " + std::to_string(c) + " ('" + child.name() +
                                        "') of the root is neither an Actor nor an ActorGroup node (not mirrored)");
        }
    }
    im.view = makeSceneView(im.root.get(), im.stamp.get(), options.matchThrong);
    im.recordingView = makeSceneView(im.root.get(), im.stamp.get(), options.matchThrong);
    im.recordingView->setCullVisitor(new RecordingCullVisitor(im.recorded));
}

OsgCrowd::~OsgCrowd() {
    for (auto& [t, m] : impl_->templates) {
        for (auto& levels : m->nodeGeodes)
            for (auto& g : levels)
                if (g) g->forgetParents();
        for (auto& g : m->rootGeodes)
            if (g) g->forgetParents();
    }
}

void OsgCrowd::setCamera(const Camera& camera) {
    for (osgUtil::SceneView* v : {impl_->view.get(), impl_->recordingView.get()}) {
        v->setViewMatrix(toOsg(camera.view()));
        v->setProjectionMatrix(toOsg(camera.projection()));
    }
}

OsgFrameTimes OsgCrowd::frame(double time) {
    Impl& im = *impl_;
    im.stamp->setFrameNumber(im.frameNumber++);
    im.stamp->setReferenceTime(time);
    im.stamp->setSimulationTime(time);
    OsgFrameTimes times;
    Stopwatch watch;
    im.view->update();
    times.updateMs = watch.elapsedMs();
    watch.restart();
    im.view->cull();
    times.cullMs = watch.elapsedMs();
    return times;
}

std::vector<VisiblePart> OsgCrowd::visibleParts() {
    impl_->recorded.clear();
    impl_->recordingView->cull();
    std::vector<VisiblePart> parts = std::move(impl_->recorded);
    impl_->recorded.clear();
    std::sort(parts.begin(), parts.end());
    return parts;
}

std::size_t OsgCrowd::nodeCount() const { return impl_->nodes; }

}  // namespace throng::peers
