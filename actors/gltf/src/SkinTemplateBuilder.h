#pragma once
// Internal: the template of one glTF skin, built from what ContentReader read. build() reads as
// its steps: sort the primitives (the skin's own, and unskinned ones below its joints); fold the
// node hierarchy into Skeleton nodes (joints, and animated nodes above them, get DOFs; the other
// nodes fold into the joint below; rigid primitives hang below their joint); merge the skin's
// primitives into one mesh and compute the joints' spheres from it; skeletal LOD from the mesh;
// the nodes and the skin; the geometric LOD levels; the clips; the Sklsroot margin and build.

#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "GltfContent.h"
#include "GltfDocument.h"
#include "throng/actors/ActorTemplate.h"
#include "throng/gltf/GltfLoadOptions.h"
#include "throng/gltf/LoadedAnimation.h"
#include "throng/gltf/LoadedCharacter.h"

namespace throng::gltf {

/// What building one skin's template made, and what of the file it used.
struct SkinTemplate {
    LoadedCharacter character;                    ///< the template and where its parts came from
    std::vector<int> rigidPrimitives;             ///< unskinned primitives it draws as joints' geometry
    std::vector<std::pair<int, int>> channelsUsed;  ///< (animation, channel) turned into clip channels
};

/// Builds the template of one skin (one builder per skin, build() once).
class SkinTemplateBuilder {
public:
    /// A builder of skin `skin` of `doc`, from `content`; `animations` name the clips, `name` is the
    /// asset's (the template is "name", or "name/<skin name>" when the file has several skins).
    SkinTemplateBuilder(GltfDocument& doc, const GltfContent& content, const std::vector<LoadedAnimation>& animations,
                        const GltfLoadOptions& options, const std::string& name, int skin);

    /// Runs the steps. Throws GltfError naming the skin, node or animation at fault.
    SkinTemplate build();

private:
    // Where a glTF node went in the skeleton: its Skeleton node, and the uniform scale and rotation
    // of the non-joint transforms folded into it (B = T(b) R(r) S(a)), which its clips must apply.
    struct JointFold {
        int skeleton = -1;                    // Skeleton node index, -1: not a Skeleton node
        double scale = 1.0;                   // a
        dquat rotation{1.0, 0.0, 0.0, 0.0};   // r
    };

    // The skin's own primitives, and the unskinned ones below each of its joints (the nearest
    // joint ancestor-or-self): those become the joint's rigid geometry.
    void sortPrimitives();
    // Depth first from the joints' common root: joints, and animated nodes above joints, become
    // Skeleton nodes with DOFs; the transforms of other nodes fold into the next one below.
    void foldNodes();
    // The Skeleton node of glTF node `node`, `above` being the folded transforms since its
    // skeleton parent. Returns its index.
    int addJointNode(int node, const dmat4& above, int skeletonParent);
    // A non-uniform scale cannot fold into a joint's DOFs: a DOF-less node keeps it. Returns the
    // index of that node, the joint's parent.
    int keepNonUniformScale(int node, const Trs& above, int skeletonParent);
    // The rigid primitives below glTF joint `node`, as DOF-less children of its Skeleton node.
    void addRigidGeometry(int node, int skeletonNode);
    // The joints' internal spheres from the merged mesh: the bind-pose vertices each joint
    // dominates, in the joint's frame. Returns what each Skeleton node moves (bind space, scaled),
    // for skeletal LOD.
    std::vector<BoundingSphere> computeJointSpheres(const MeshData& mesh);
    // Hands the Skeleton nodes and the skin to the template builder; returns the skin's index.
    int addNodesAndSkin();
    // The skinned mesh as the root's vaLod levels: as it is, or one simplified mesh per
    // GltfLoadOptions::lodLevels entry (each level's surface error recorded).
    void addMeshLevels(const std::shared_ptr<MeshData>& mesh, int skinIndex);
    // One clip per animation that drives a Skeleton node of this template.
    void addClips();
    // Morph-weight channel `in` as one MorphWeight clip channel per target of its node's mesh
    // (indices into `morphChannels`), into `out`, skipping channels `weighted` already holds (it
    // gains the new ones). Returns whether any was added.
    bool addWeightChannels(const ReadChannel& in, const std::vector<std::string>& morphChannels,
                           std::set<std::uint32_t>& weighted, std::vector<ClipChannel>& out) const;
    // Channel `in` of animation `a` as a clip channel of Skeleton node `f.skeleton`: translations
    // carry the folded scale and rotation, quaternion keys are normalised.
    ClipChannel clipChannel(const ReadChannel& in, const JointFold& f, std::size_t a) const;
    // The Sklsroot margin (stated, or 1% of the rest extent, at least 5 cm), then the template.
    void buildTemplate();
    // `n`, or "n#2", "n#3"... when a Skeleton node already has that name.
    std::string uniqueName(const std::string& n);

    GltfDocument& doc_;
    const tinygltf::Model& m_;
    const GltfContent& c_;
    const std::vector<LoadedAnimation>& animations_;
    const GltfLoadOptions& options_;
    const std::string name_;
    const int s_;
    const std::vector<int>& joints_;  // glTF nodes of the skin's joints
    const std::string skinName_;
    ActorTemplateBuilder builder_;
    SkinTemplate out_;
    std::map<int, int> jointIndex_;  // glTF node -> skin joint k
    std::vector<int> skinned_;       // the skin's own primitives
    std::map<int, std::vector<int>> rigidUnder_;  // glTF joint node -> rigid primitives below it
    std::vector<SkeletonNode> nodes_;
    std::set<std::string> names_;
    std::vector<JointFold> fold_;       // per glTF node
    std::vector<int> skeletonOfJoint_;  // per skin joint k: its Skeleton node
    std::vector<dvec3> extentPoints_;   // joints, rigid and skinned vertices: the rest extent
};

}  // namespace throng::gltf
