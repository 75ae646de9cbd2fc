#pragma once
// The joints a frame shows, read from its draw list: for every actor drawn skinned, each skin
// joint's world position as its palette places it (a joint deactivated by skeletal LOD where it is
// carried by its active ancestor), and for actors drawn from a key-pose cache, where the cached
// pose (or the blend of two) puts it. So two settings of a frame can be compared pose for pose,
// whatever made the pose (behavioural or skeletal LOD, a key-pose cache). Impostors have no joints.

#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "throng/actors/Crowd.h"
#include "throng/actors/JointError.h"
#include "throng/scenegraph/DrawList.h"

namespace throng::testkit {

/// World positions of the skinned joints of the actors of one draw list.
class DrawnJoints {
public:
    /// Reads the joints of every actor of `crowd` drawn in `list` as a skinned mesh or a key-pose.
    void collect(const DrawList& list, const Crowd& crowd);
    /// Actors with joints.
    std::size_t actors() const { return byActor_.size(); }
    /// Adds to `error` the distance of every joint of an actor both hold to `reference`'s.
    void compare(const DrawnJoints& reference, JointError& error) const;

private:
    struct Joints {
        std::vector<Vec3> position;    // per Skeleton node
        std::vector<std::uint8_t> set; // whether the node's position was drawn
    };
    const std::vector<Vec3>& bindPositions(const ActorTemplate& tmpl);
    std::unordered_map<std::uint32_t, Joints> byActor_;
    std::unordered_map<const ActorTemplate*, std::vector<Vec3>> bind_;  // joint origins in bind pose, model space
};

}  // namespace throng::testkit
