#include "throng/actors/ActorTemplate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

#include "throng/actors/SkeletonPose.h"
#include "throng/scenegraph/MeshDrawable.h"

namespace throng {
namespace {

std::string fmt(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

bool finite3(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Largest absolute value a 1-value DOF can take (its limits), for the reach bound.
double dofReach(const Dof& d) { return std::max(std::abs(double(d.min)), std::abs(double(d.max))); }

// The morph channels of a template's drawables: names in order of first appearance (nodes in
// order, each's levels in order, then the actor-level vaLod), the first default weight of each,
// and per node (nodeCount() for the actor-level vaLod) and level the channel of each target.
struct MorphChannels {
    std::vector<std::string> names;
    std::vector<float> rest;
    std::vector<std::vector<std::vector<std::uint32_t>>> maps;
    bool any = false;
};

MorphChannels collectMorphChannels(const std::vector<SkeletonNode>& nodes, const VaLod& rootGeometry) {
    MorphChannels out;
    out.maps.resize(nodes.size() + 1);
    auto mapLevels = [&](const VaLod& lod, std::vector<std::vector<std::uint32_t>>& map) {
        map.resize(lod.levels().size());
        for (std::size_t l = 0; l < lod.levels().size(); ++l) {
            const auto* mesh = dynamic_cast<const MeshDrawable*>(lod.levels()[l].drawable.get());
            if (!mesh) continue;
            for (const MorphTarget& target : mesh->mesh().morphTargets) {
                out.any = true;
                const auto found = std::find(out.names.begin(), out.names.end(), target.name);
                if (found == out.names.end()) {
                    out.names.push_back(target.name);
                    out.rest.push_back(target.defaultWeight);
                }
                map[l].push_back(static_cast<std::uint32_t>(std::find(out.names.begin(), out.names.end(), target.name) - out.names.begin()));
            }
        }
    };
    for (std::size_t i = 0; i < nodes.size(); ++i) mapLevels(nodes[i].geometry, out.maps[i]);
    mapLevels(rootGeometry, out.maps[nodes.size()]);
    return out;
}

}  // namespace

std::vector<std::string> ActorTemplateBuilder::morphChannels() const { return collectMorphChannels(nodes_, rootGeometry_).names; }

int ActorTemplate::findNode(std::string_view name) const {
    for (std::size_t i = 0; i < nodes_.size(); ++i)
        if (nodes_[i].name == name) return static_cast<int>(i);
    return -1;
}

int ActorTemplate::findClip(std::string_view name) const {
    for (std::size_t i = 0; i < clips_.size(); ++i)
        if (clips_[i]->name() == name) return static_cast<int>(i);
    return -1;
}

int ActorTemplate::findMorphChannel(std::string_view name) const {
    for (std::size_t i = 0; i < morphChannels_.size(); ++i)
        if (morphChannels_[i] == name) return static_cast<int>(i);
    return -1;
}

std::size_t ActorTemplate::sharedBytes() const {
    std::size_t bytes = sizeof(ActorTemplate);
    std::set<const void*> meshes;
    auto countDrawables = [&](const VaLod& lod) {
        for (const VaLodLevel& l : lod.levels()) {
            auto* mesh = dynamic_cast<const MeshDrawable*>(l.drawable.get());
            if (!mesh || !meshes.insert(&mesh->mesh()).second) continue;
            const MeshData& m = mesh->mesh();
            for (const MorphTarget& t : m.morphTargets) bytes += (t.positions.size() + t.normals.size()) * sizeof(glm::vec3);
            bytes += m.positions.size() * sizeof(glm::vec3) + m.normals.size() * sizeof(glm::vec3) +
                     m.texcoords.size() * sizeof(glm::vec2) + m.indices.size() * sizeof(std::uint32_t) +
                     (m.joints0.size() + m.joints1.size()) * (sizeof(glm::u16vec4) + sizeof(glm::vec4));
            if (m.baseColorTexture && meshes.insert(m.baseColorTexture.get()).second)
                bytes += m.baseColorTexture->rgba.size();
        }
    };
    for (const SkeletonNode& n : nodes_) {
        bytes += sizeof(SkeletonNode) + n.name.size() + n.dofs.size() * sizeof(Dof) +
                 n.geometry.levels().size() * sizeof(VaLodLevel);
        countDrawables(n.geometry);
    }
    countDrawables(rootGeometry_);
    bytes += (subtreeEnd_.size() + dofOffset_.size() + firstDof_.size() + dofValueOffset_.size()) * sizeof(std::uint32_t) + dofKind_.size() * sizeof(DofKind) +
             restDofs_.size() * sizeof(float);
    for (const auto& c : clips_)
        for (const ClipChannel& ch : c->channels())
            bytes += sizeof(ClipChannel) + (ch.times.size() + ch.values.size()) * sizeof(float);
    return bytes;
}

ActorTemplateBuilder::ActorTemplateBuilder(std::string name) : name_(std::move(name)) {}

int ActorTemplateBuilder::addNode(SkeletonNode node) {
    const std::string who = "template '" + name_ + "': Skeleton node '" + node.name + "'";
    if (node.name.empty()) throw std::invalid_argument("template '" + name_ + "': a Skeleton node has no name");
    for (const SkeletonNode& n : nodes_)
        if (n.name == node.name) throw std::invalid_argument(who + ": the name is already used");
    if (node.parent != -1) {
        bool ok = false;
        for (int a = static_cast<int>(nodes_.size()) - 1; a >= 0; a = nodes_[static_cast<std::size_t>(a)].parent)
            if (a == node.parent) {
                ok = true;
                break;
            }
        if (!ok)
            throw std::invalid_argument(who + ": parent " + std::to_string(node.parent) +
                                        " is not the previous node or one of its ancestors (nodes must come in depth-first order)");
    }
    if (!finite3(node.restTranslation) || !finite3(node.restScale) || !std::isfinite(node.restRotation.w) ||
        !std::isfinite(node.restRotation.x) || !std::isfinite(node.restRotation.y) || !std::isfinite(node.restRotation.z))
        throw std::invalid_argument(who + ": has a non-finite rest transform");
    const float qlen = glm::length(node.restRotation);
    if (!(qlen > 0.0f)) throw std::invalid_argument(who + ": rest rotation is a zero quaternion");
    node.restRotation = node.restRotation / qlen;
    if (std::isnan(node.deactivationDistance) || node.deactivationDistance <= 0.0)
        throw std::invalid_argument(who + ": deactivation distance must be positive, got " + fmt(node.deactivationDistance));
    for (std::size_t d = 0; d < node.dofs.size(); ++d) {
        Dof& dof = node.dofs[d];
        const std::string which = who + ", DOF " + std::to_string(d);
        for (float v : dof.rest)
            if (!std::isfinite(v)) throw std::invalid_argument(which + ": rest value is not finite");
        if (dof.kind == DofKind::RotateAxis || dof.kind == DofKind::TranslateAxis) {
            const float len = glm::length(dof.axis);
            if (!finite3(dof.axis) || !(len > 0.0f)) throw std::invalid_argument(which + ": axis is zero or not finite");
            dof.axis /= len;
            if (std::isnan(dof.min) || std::isnan(dof.max) || dof.min > dof.max)
                throw std::invalid_argument(which + ": limits [" + fmt(dof.min) + ", " + fmt(dof.max) + "] are not ordered");
            if (dof.rest[0] < dof.min || dof.rest[0] > dof.max)
                throw std::invalid_argument(which + ": rest value " + fmt(dof.rest[0]) + " is outside its limits");
        } else if (dof.kind == DofKind::Orientation) {
            const float len = std::sqrt(dof.rest[0] * dof.rest[0] + dof.rest[1] * dof.rest[1] +
                                        dof.rest[2] * dof.rest[2] + dof.rest[3] * dof.rest[3]);
            if (!(len > 0.0f)) throw std::invalid_argument(which + ": rest orientation is a zero quaternion");
            for (float& v : dof.rest) v /= len;
        }
    }
    nodes_.push_back(std::move(node));
    return static_cast<int>(nodes_.size()) - 1;
}

int ActorTemplateBuilder::addSkin(Skin skin) {
    skins_.push_back(std::move(skin));
    return static_cast<int>(skins_.size()) - 1;
}

void ActorTemplateBuilder::addClip(std::shared_ptr<const AnimationClip> clip) {
    if (!clip) throw std::invalid_argument("template '" + name_ + "': addClip: argument 'clip' is null");
    clips_.push_back(std::move(clip));
}

void ActorTemplateBuilder::setSkeletonRootMargin(double metres) {
    if (!std::isfinite(metres) || metres < 0.0)
        throw std::invalid_argument("template '" + name_ + "': Sklsroot margin must be finite and >= 0, got " + fmt(metres));
    margin_ = metres;
}

void ActorTemplateBuilder::setRadiusSampleRate(double hertz) {
    if (!std::isfinite(hertz) || hertz <= 0.0)
        throw std::invalid_argument("template '" + name_ + "': radius sample rate must be positive, got " + fmt(hertz));
    sampleRate_ = hertz;
}

std::shared_ptr<const ActorTemplate> ActorTemplateBuilder::build() {
    const std::string who = "template '" + name_ + "'";
    if (nodes_.empty() && rootGeometry_.empty()) throw std::invalid_argument(who + ": has neither Skeleton nodes nor geometry");

    // Skeletal LOD must agree with the vaLod transitions (seed 002 §5.2, Fig. 5).
    for (const SkeletonNode& n : nodes_) {
        const double drawn = n.geometry.lastDrawnDistance();
        if (drawn > n.deactivationDistance)
            throw std::invalid_argument(who + ": Skeleton node '" + n.name + "' still shows geometry up to " + fmt(drawn) +
                                        " m but is deactivated at " + fmt(n.deactivationDistance) +
                                        " m (a deactivated node must not keep separate geometry)");
        if (n.parent >= 0) {
            const SkeletonNode& p = nodes_[static_cast<std::size_t>(n.parent)];
            if (n.deactivationDistance > p.deactivationDistance)
                throw std::invalid_argument(who + ": Skeleton node '" + n.name + "' stays active up to " +
                                            fmt(n.deactivationDistance) + " m but its parent '" + p.name +
                                            "' is deactivated at " + fmt(p.deactivationDistance) + " m");
        }
    }

    // Skins: joints must exist, and every skinned level's vertices must name joints of its skin.
    for (std::size_t k = 0; k < skins_.size(); ++k)
        for (std::uint32_t j : skins_[k].joints)
            if (j >= nodes_.size())
                throw std::invalid_argument(who + ": skin '" + skins_[k].name + "' names node " + std::to_string(j) +
                                            " of " + std::to_string(nodes_.size()));
    for (const VaLodLevel& l : rootGeometry_.levels()) {
        if (l.skin < 0 || !l.drawable) continue;
        if (static_cast<std::size_t>(l.skin) >= skins_.size())
            throw std::invalid_argument(who + ": a skinned level uses skin " + std::to_string(l.skin) + " of " +
                                        std::to_string(skins_.size()));
        const auto* mesh = dynamic_cast<const MeshDrawable*>(l.drawable.get());
        if (!mesh || !mesh->mesh().skinned())
            throw std::invalid_argument(who + ": skinned level '" + l.drawable->name() + "' is not a skinned mesh");
        const std::size_t joints = skins_[static_cast<std::size_t>(l.skin)].joints.size();
        for (const auto* set : {&mesh->mesh().joints0, &mesh->mesh().joints1})
            for (const glm::u16vec4& v : *set)
                for (int c = 0; c < 4; ++c)
                    if (v[c] >= joints)
                        throw std::invalid_argument(who + ": skinned mesh '" + l.drawable->name() + "' refers to joint " +
                                                    std::to_string(v[c]) + " but its skin has " + std::to_string(joints));
    }
    for (const SkeletonNode& n : nodes_)
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                if (!std::isfinite(n.inverseBind[c][r]))
                    throw std::invalid_argument(who + ": Skeleton node '" + n.name + "' has a non-finite inverse bind matrix");

    std::shared_ptr<ActorTemplate> t(new ActorTemplate());
    t->name_ = name_;
    t->nodes_ = nodes_;
    t->rootGeometry_ = rootGeometry_;
    t->skins_ = skins_;
    t->margin_ = margin_;
    const std::size_t n = nodes_.size();

    t->subtreeEnd_.resize(n);
    for (std::size_t i = 0; i < n; ++i) t->subtreeEnd_[i] = static_cast<std::uint32_t>(i + 1);
    for (std::size_t i = n; i-- > 0;)
        if (nodes_[i].parent >= 0) {
            auto& end = t->subtreeEnd_[static_cast<std::size_t>(nodes_[i].parent)];
            end = std::max(end, t->subtreeEnd_[i]);
        }

    std::uint32_t values = 0, dofs = 0;
    t->dofOffset_.resize(n);
    t->firstDof_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        t->dofOffset_[i] = values;
        t->firstDof_[i] = dofs;
        for (const Dof& d : nodes_[i].dofs) {
            t->dofValueOffset_.push_back(values);
            t->dofKind_.push_back(d.kind);
            for (int k = 0; k < dofValueCount(d.kind); ++k) t->restDofs_.push_back(d.rest[static_cast<std::size_t>(k)]);
            values += static_cast<std::uint32_t>(dofValueCount(d.kind));
            ++dofs;
        }
    }
    // Morph channels: one weight per target name, after the skeleton's values; each drawable's
    // targets mapped to them.
    t->morphWeightOffset_ = values;
    {
        MorphChannels channels = collectMorphChannels(nodes_, rootGeometry_);
        t->morphChannels_ = std::move(channels.names);
        t->restDofs_.insert(t->restDofs_.end(), channels.rest.begin(), channels.rest.end());
        if (channels.any) t->morphMaps_ = std::move(channels.maps);
    }
    values += static_cast<std::uint32_t>(t->morphChannels_.size());
    t->dofValueCount_ = values;
    t->dofCount_ = dofs;

    std::size_t spheres = n;  // one subtree sphere per node
    for (SkeletonNode& node : t->nodes_) {
        if (!node.geometrySphere.valid()) node.geometrySphere = node.geometry.bound();
        if (node.geometrySphere.valid()) ++spheres;
    }
    t->internalSphereCount_ = spheres;

    // Clips: every channel must fit the skeleton.
    for (const auto& clip : clips_) {
        for (std::size_t i = 0; i < clip->channels().size(); ++i) {
            const ClipChannel& c = clip->channels()[i];
            const std::string where = who + ", clip '" + clip->name() + "', channel " + std::to_string(i);
            int width = 0;
            if (c.target == ClipChannel::Target::MorphWeight) {
                if (c.node >= t->morphChannels_.size())
                    throw std::invalid_argument(where + ": targets morph channel " + std::to_string(c.node) + " of " +
                                                std::to_string(t->morphChannels_.size()));
                width = 1;
            } else if (c.target == ClipChannel::Target::NodeDof) {
                if (c.node >= n) throw std::invalid_argument(where + ": targets node " + std::to_string(c.node) + " of " + std::to_string(n));
                const SkeletonNode& node = t->nodes_[c.node];
                if (c.dof >= node.dofs.size())
                    throw std::invalid_argument(where + ": targets DOF " + std::to_string(c.dof) + " of node '" + node.name +
                                                "', which has " + std::to_string(node.dofs.size()));
                width = dofValueCount(node.dofs[c.dof].kind);
            } else {
                width = c.target == ClipChannel::Target::RootTranslation ? 3 : 4;
            }
            const std::size_t expected = valuesPerKey(c.interpolation, width) * c.times.size();
            if (c.values.size() != expected)
                throw std::invalid_argument(where + ": has " + std::to_string(c.values.size()) + " values, expected " +
                                            std::to_string(expected) + " for " + std::to_string(c.times.size()) + " keys");
        }
        t->clips_.push_back(clip);
    }

    // Reach bound: chains at full stretch within the DOF limits.
    std::vector<double> reach(n, 0.0), scale(n, 1.0);
    double reachRadius = 0.0;
    const BoundingSphere rootBound = rootGeometry_.bound();
    if (rootBound.valid()) reachRadius = glm::length(rootBound.center()) + rootBound.radius();
    for (std::size_t i = 0; i < n; ++i) {
        const SkeletonNode& node = t->nodes_[i];
        const double parentReach = node.parent >= 0 ? reach[static_cast<std::size_t>(node.parent)] : 0.0;
        const double parentScale = node.parent >= 0 ? scale[static_cast<std::size_t>(node.parent)] : 1.0;
        double offset = glm::length(glm::dvec3(node.restTranslation));
        double ownScale = std::max({std::abs(double(node.restScale.x)), std::abs(double(node.restScale.y)),
                                    std::abs(double(node.restScale.z))});
        for (const Dof& d : node.dofs) {
            if (d.kind == DofKind::TranslateAxis) offset += dofReach(d);
            if (d.kind == DofKind::Position || d.kind == DofKind::Scale) {
                offset = std::numeric_limits<double>::infinity();  // unbounded: no guaranteed reach
                ownScale = std::numeric_limits<double>::infinity();
            }
        }
        reach[i] = parentReach + parentScale * offset;
        scale[i] = parentScale * ownScale;
        if (node.geometrySphere.valid())
            reachRadius = std::max(reachRadius, reach[i] + scale[i] * (glm::length(node.geometrySphere.center()) +
                                                                       node.geometrySphere.radius()));
        else
            reachRadius = std::max(reachRadius, reach[i]);
    }
    t->reachRadius_ = reachRadius;
    t->chainReach_ = reach;
    t->chainScale_ = scale;
    t->sampledReach_.assign(n, 0.0);
    t->sampledScale_.assign(n, 0.0);

    // Sampled radius: every key time of every clip, plus a uniform sampling, plus the rest pose.
    // Each part's geometry sphere is the union of its levels, so every level is covered.
    std::vector<float> pose(t->restDofs_.begin(), t->restDofs_.end());
    std::vector<Affine> model(n);
    std::vector<BoundingSphere> geometry(n), subtree(n);
    auto poseRadius = [&]() {
        computeModelTransforms(*t, pose, {}, model);
        for (std::size_t i = 0; i < n; ++i) {
            t->sampledReach_[i] = std::max(t->sampledReach_[i], double(glm::length(model[i].translation)) + margin_);
            t->sampledScale_[i] = std::max(t->sampledScale_[i], maxScaleFactor(model[i].toDMat4()));
        }
        // The farthest any part gets: culling needs every part inside the Sklsroot Bsphere.
        computeInternalSpheres(*t, model, {}, geometry, subtree);
        double far = rootBound.valid() ? glm::length(rootBound.center()) + rootBound.radius() : 0.0;
        for (const BoundingSphere& g : geometry)
            if (g.valid()) far = std::max(far, glm::length(g.center()) + g.radius());
        return far;
    };
    double sampled = poseRadius();
    for (const auto& clip : t->clips_) {
        std::vector<double> times;
        for (const ClipChannel& c : clip->channels()) times.insert(times.end(), c.times.begin(), c.times.end());
        const auto steps = static_cast<std::size_t>(std::ceil(clip->duration() * sampleRate_));
        for (std::size_t k = 0; k <= steps; ++k)
            times.push_back(std::min(clip->duration(), static_cast<double>(k) / sampleRate_));
        for (double time : times) {
            std::copy(t->restDofs_.begin(), t->restDofs_.end(), pose.begin());
            clip->sample(*t, time, false, {}, pose);
            sampled = std::max(sampled, poseRadius());
        }
    }
    t->skeletonRootRadius_ = std::min(sampled + margin_, reachRadius);
    return t;
}

}  // namespace throng
