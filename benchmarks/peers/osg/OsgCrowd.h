#pragma once
// The crowd of a Throng scene rebuilt in OpenSceneGraph 3.6, to time a generic scenegraph on the
// very same actors: one osg::MatrixTransform per Reference Point, Skeleton Root and Skeleton node,
// one osg::LOD per node with geometry (and one for the actor-level geometry), read from the Throng
// template itself so the two cannot drift apart. An update callback per actor, run by
// osgUtil::UpdateVisitor, sets every matrix from the same behaviour and clip at the same time;
// osgUtil::SceneView culls with osgUtil::CullVisitor. No GL context is needed: nothing is drawn.
//
// OSG is configured to decide what Throng decides (see the README, "OpenSceneGraph side by side"):
// the whole frustum is culled (near and far planes included, no near/far computation), small-feature
// culling is off, every LOD measures its distance from the actor's Skeleton Root (as Throng's one
// eye distance per actor) rather than from its own bound's centre, and each geometry leaf is culled
// by the same sphere as in Throng.

#include <cstddef>
#include <memory>
#include <vector>

#include "VisibleParts.h"

namespace throng {
class Camera;
class Crowd;
class Group;
}  // namespace throng

namespace throng::peers {

/// Milliseconds one OSG frame took.
struct OsgFrameTimes {
    double updateMs = 0.0;  ///< UpdateVisitor (every actor's callback) and the bounds SceneView::update recomputes
    double cullMs = 0.0;    ///< SceneView::cull: CullVisitor, render bins sorted
    /// Update and cull.
    double totalMs() const { return updateMs + cullMs; }
};

/// How the OSG copy is set up.
struct OsgCrowdOptions {
    /// true: OSG set to decide what Throng decides (the comparison). false: OSG as it comes: the
    /// four side planes culled with near and far computed, small-feature culling (2 pixels), each
    /// LOD measuring from its own bound's centre, leaves culled by their geometry's boxes; the
    /// visible sets then differ from Throng's, which shows what each setting changes.
    bool matchThrong = true;
};

/// An OpenSceneGraph copy of the actors of a Throng scene, processed by OSG's own visitors.
class OsgCrowd {
public:
    /// Mirrors the actors under `root`: a Group whose children are Actor or ActorGroup nodes of
    /// `crowd` (which must outlive this object). Throws std::invalid_argument naming the node or
    /// actor that cannot be mirrored: another kind of node, a behaviour that is not closed-form
    /// key-framing, a skinned level, a held object, or a scaled Skeleton node (an OSG LOD measures
    /// distances in its node's frame).
    OsgCrowd(const Crowd& crowd, const Group& root, const OsgCrowdOptions& options = {});
    /// Takes the scene apart in time linear in its size.
    ~OsgCrowd();
    OsgCrowd(const OsgCrowd&) = delete;
    OsgCrowd& operator=(const OsgCrowd&) = delete;

    /// Views the scene from `camera` (its view and projection matrices).
    void setCamera(const Camera& camera);
    /// Runs one frame at `time`: update traversal, then cull. Returns their times.
    OsgFrameTimes frame(double time);
    /// Culls the state of the last frame again with a visitor that records every drawable reaching
    /// the render bins, and returns them as (actor, part, level), sorted. Not for timing.
    std::vector<VisiblePart> visibleParts();

    /// Nodes in the OSG scene (geometry leaves shared between actors counted once).
    std::size_t nodeCount() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace throng::peers
