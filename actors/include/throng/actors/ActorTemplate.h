#pragma once
// An actor template: the skeleton description (Skeleton nodes in depth-first order), the actor's
// own vaLod (geometry in the Skeleton Root frame), its clips and the derived data every clone
// shares: DOF layout, subtree ranges, geometry spheres and the Sklsroot radius. Immutable once built.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "throng/actors/AnimationClip.h"
#include "throng/actors/SkeletonNode.h"
#include "throng/actors/Skin.h"
#include "throng/actors/VaLod.h"

namespace throng {

class ActorTemplateBuilder;

/// What a template costs in memory.
struct TemplateMemory {
    std::size_t sharedBytes = 0;     ///< skeleton, clips and geometry, paid once per template
    std::size_t perCloneBytes = 0;   ///< state of one more clone (see Crowd::bytesPerActor)
};

/// A shared, immutable description of one kind of actor.
class ActorTemplate {
public:
    /// Name.
    const std::string& name() const { return name_; }
    /// Skeleton nodes in depth-first order: a parent comes before its children, and node i's
    /// subtree is the index range [i, subtreeEnd(i)).
    std::span<const SkeletonNode> nodes() const { return nodes_; }
    /// Number of Skeleton nodes.
    std::size_t nodeCount() const { return nodes_.size(); }
    /// Index of the node named `name`, or -1.
    int findNode(std::string_view name) const;
    /// One past the last node of node i's subtree.
    std::uint32_t subtreeEnd(std::size_t i) const { return subtreeEnd_[i]; }

    /// Offset of node i's first DOF value in a pose's DOF array.
    std::uint32_t dofOffset(std::size_t i) const { return dofOffset_[i]; }
    /// Offset of the first value of DOF `dof` of node `node` in a pose's DOF array.
    std::uint32_t dofValueOffset(std::size_t node, std::size_t dof) const { return dofValueOffset_[firstDof_[node] + dof]; }
    /// Kind of DOF `dof` of node `node` (what nodes()[node].dofs[dof].kind says, from a flat table
    /// that sampling a clip reads once per channel).
    DofKind dofKind(std::size_t node, std::size_t dof) const { return dofKind_[firstDof_[node] + dof]; }
    /// Number of DOF values of a pose: the skeleton's, then one weight per morph channel.
    std::uint32_t dofValueCount() const { return dofValueCount_; }

    /// Morph channels: the names of the morph targets of the template's meshes, one weight each
    /// (meshes with a target of the same name share its weight), in order of first appearance.
    std::span<const std::string> morphChannels() const { return morphChannels_; }
    /// Index of the morph channel named `name`, or -1.
    int findMorphChannel(std::string_view name) const;
    /// Offset of morph channel 0's weight in a pose's DOF array (after the skeleton's values).
    std::uint32_t morphWeightOffset() const { return morphWeightOffset_; }
    /// The morph channel of each morph target of the drawable of vaLod level `level` of node
    /// `node` (nodeCount() for the actor-level vaLod); empty when it has none (or no such level).
    std::span<const std::uint32_t> morphChannelsOf(std::size_t node, std::size_t level) const {
        if (morphMaps_.empty() || node >= morphMaps_.size() || level >= morphMaps_[node].size()) return {};
        return morphMaps_[node][level];
    }
    /// Number of DOFs (not values) of the whole skeleton (19 for the seed's humanoid).
    std::uint32_t dofCount() const { return dofCount_; }
    /// DOF values of the rest pose.
    std::span<const float> restDofs() const { return restDofs_; }

    /// The actor's own vaLod: geometry in the Skeleton Root frame (the seed's actor-level LOD).
    const VaLod& rootGeometry() const { return rootGeometry_; }
    /// Skins deforming the skinned levels of the actor's vaLod.
    std::span<const Skin> skins() const { return skins_; }
    /// Clips (key-framing tables) this template plays.
    std::span<const std::shared_ptr<const AnimationClip>> clips() const { return clips_; }
    /// Index of the clip named `name`, or -1.
    int findClip(std::string_view name) const;

    /// Radius of the Sklsroot Bsphere: every geometry sphere in every sampled pose of every clip,
    /// plus the margin given at build time. Valid for behaviours that play this template's clips.
    double skeletonRootRadius() const { return skeletonRootRadius_; }
    /// A radius no pose within the DOF limits can exceed (chains at full stretch): valid for any
    /// behaviour; infinite if a translation or scale DOF is unbounded.
    double reachRadius() const { return reachRadius_; }
    /// Farthest node i's frame origin gets from the Skeleton Root, and its largest scale, over the
    /// sampled clip poses (`sampled`) or over every pose within the DOF limits (otherwise; infinite
    /// when unbounded). For placing held objects.
    double nodeReach(std::size_t i, bool sampled) const { return sampled ? sampledReach_[i] : chainReach_[i]; }
    /// Largest scale of node i's frame, as nodeReach.
    double nodeScale(std::size_t i, bool sampled) const { return sampled ? sampledScale_[i] : chainScale_[i]; }
    /// The margin added to the sampled radius (metres).
    double skeletonRootMargin() const { return margin_; }
    /// Number of internal bounding spheres per actor: one per node with geometry, one per subtree.
    std::size_t internalSphereCount() const { return internalSphereCount_; }

    /// Memory shared by clones (per-clone state is the Crowd's: see Crowd::bytesPerActor).
    std::size_t sharedBytes() const;

private:
    friend class ActorTemplateBuilder;
    ActorTemplate() = default;

    std::string name_;
    std::vector<SkeletonNode> nodes_;
    std::vector<std::uint32_t> subtreeEnd_;
    std::vector<std::uint32_t> dofOffset_;
    std::vector<std::uint32_t> firstDof_;
    std::vector<std::uint32_t> dofValueOffset_;
    std::vector<DofKind> dofKind_;
    std::uint32_t dofValueCount_ = 0;
    std::uint32_t dofCount_ = 0;
    std::vector<float> restDofs_;
    std::vector<std::string> morphChannels_;
    std::uint32_t morphWeightOffset_ = 0;
    std::vector<std::vector<std::vector<std::uint32_t>>> morphMaps_;  // [node][level]: empty without morph targets
    VaLod rootGeometry_;
    std::vector<Skin> skins_;
    std::vector<std::shared_ptr<const AnimationClip>> clips_;
    std::vector<double> chainReach_, chainScale_, sampledReach_, sampledScale_;
    double skeletonRootRadius_ = 0.0;
    double reachRadius_ = 0.0;
    double margin_ = 0.0;
    std::size_t internalSphereCount_ = 0;
};

/// Assembles and validates an ActorTemplate.
class ActorTemplateBuilder {
public:
    /// Starts a template named `name`.
    explicit ActorTemplateBuilder(std::string name);

    /// Adds a node and returns its index. Nodes come in depth-first order: the parent is -1 (under
    /// the Skeleton Root), the previous node, or one of its ancestors. Throws std::invalid_argument
    /// naming the node on a bad parent, duplicate name, non-finite value, or a DOF with a zero
    /// axis, min > max, or a rest value outside its limits.
    int addNode(SkeletonNode node);
    /// The actor-level vaLod (geometry in the Skeleton Root frame), to add levels to. Skinned
    /// meshes are levels of it, with the index of their skin.
    VaLod& rootGeometry() { return rootGeometry_; }
    /// Adds a skin and returns its index. Checked at build(): joints must exist.
    int addSkin(Skin skin);
    /// Adds a clip. Throws std::invalid_argument naming the clip and channel if a channel targets a
    /// node or DOF that does not exist or its values do not fit the DOF.
    void addClip(std::shared_ptr<const AnimationClip> clip);
    /// The morph channels the template will have with the nodes and vaLod levels added so far
    /// (ActorTemplate::morphChannels): what a clip's MorphWeight channels index.
    std::vector<std::string> morphChannels() const;
    /// Margin added to the Sklsroot radius sampled from the clips (default 0.05 m).
    void setSkeletonRootMargin(double metres);
    /// Sampling rate of the clips for the Sklsroot radius, besides every key time (default 60 Hz).
    void setRadiusSampleRate(double hertz);

    /// Validates (skeletal LOD against vaLod, see below) and builds the template. Throws
    /// std::invalid_argument naming the node when a node's geometry is still shown beyond its
    /// deactivation distance, or a node stays active beyond its parent's deactivation distance.
    std::shared_ptr<const ActorTemplate> build();

private:
    std::string name_;
    std::vector<SkeletonNode> nodes_;
    VaLod rootGeometry_;
    std::vector<Skin> skins_;
    std::vector<std::shared_ptr<const AnimationClip>> clips_;
    double margin_ = 0.05;
    double sampleRate_ = 60.0;
};

}  // namespace throng
