#include "throng/render/FeatureTrack.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>

namespace throng {

ViewBasis viewBasis(const glm::vec3& toEye) {
    const float len = glm::length(toEye);
    if (!(len > 0.0f) || !std::isfinite(len)) throw std::invalid_argument("viewBasis: the eye direction is zero or not finite");
    ViewBasis b;
    b.toEye = toEye / len;
    // glm::lookAt's axes for an eye at centre + toEye, up +Y: right = forward x up, up = right x forward.
    const glm::vec3 forward = -b.toEye;
    const glm::vec3 right = glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f));
    const float rightLen = glm::length(right);
    if (!(rightLen > 1e-6f)) throw std::invalid_argument("viewBasis: the eye direction is vertical (no image x axis)");
    b.right = right / rightLen;
    b.up = glm::cross(b.right, forward);
    return b;
}

FeatureTrack::FeatureTrack(std::size_t bones, int keyframes, const glm::vec3& centre, float radius, int cellSize)
    : keyframes_(keyframes), centre_(centre), radius_(radius), cellSize_(cellSize) {
    if (keyframes < 1) throw std::invalid_argument("FeatureTrack: at least one key-frame, got " + std::to_string(keyframes));
    if (!(radius > 0.0f) || !std::isfinite(radius)) throw std::invalid_argument("FeatureTrack: the radius must be positive and finite");
    if (cellSize < 1) throw std::invalid_argument("FeatureTrack: the cell size must be positive");
    if (!std::isfinite(centre.x) || !std::isfinite(centre.y) || !std::isfinite(centre.z))
        throw std::invalid_argument("FeatureTrack: the centre is not finite");
    joints_.assign(bones * static_cast<std::size_t>(keyframes) * 2, centre);
    radii_.assign(bones, 0.0f);
    nodes_.resize(bones);
    limbs_.resize(bones);
    for (std::size_t i = 0; i < bones; ++i) {
        nodes_[i] = {static_cast<std::uint32_t>(2 * i), static_cast<std::uint32_t>(2 * i + 1)};
        limbs_[i] = static_cast<std::uint32_t>(i);
    }
}

std::size_t FeatureTrack::index(int keyframe, std::size_t bone) const {
    if (keyframe < 0 || keyframe >= keyframes_ || bone >= nodes_.size())
        throw std::invalid_argument("FeatureTrack: key-frame " + std::to_string(keyframe) + " bone " + std::to_string(bone) +
                                    " out of range");
    return static_cast<std::size_t>(keyframe) * nodes_.size() + bone;
}

void FeatureTrack::setJoints(int keyframe, std::span<const glm::vec3> parents, std::span<const glm::vec3> children) {
    if (parents.size() != nodes_.size() || children.size() != nodes_.size())
        throw std::invalid_argument("FeatureTrack::setJoints: " + std::to_string(parents.size()) + " and " +
                                    std::to_string(children.size()) + " joints for " + std::to_string(nodes_.size()) + " bones");
    if (keyframe < 0 || keyframe >= keyframes_)
        throw std::invalid_argument("FeatureTrack::setJoints: key-frame " + std::to_string(keyframe) + " out of range");
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
        for (const glm::vec3& p : {parents[i], children[i]})
            if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                throw std::invalid_argument("FeatureTrack::setJoints: joint of bone " + std::to_string(i) + " is not finite");
        joints_[index(keyframe, i) * 2] = parents[i];
        joints_[index(keyframe, i) * 2 + 1] = children[i];
    }
}

void FeatureTrack::setRadii(std::vector<float> radii) {
    if (radii.size() != nodes_.size())
        throw std::invalid_argument("FeatureTrack::setRadii: " + std::to_string(radii.size()) + " radii for " +
                                    std::to_string(nodes_.size()) + " bones");
    for (std::size_t i = 0; i < radii.size(); ++i)
        if (!(radii[i] >= 0.0f) || !std::isfinite(radii[i]))
            throw std::invalid_argument("FeatureTrack::setRadii: radius " + std::to_string(i) + " is negative or not finite");
    radii_ = std::move(radii);
}

void FeatureTrack::setTopology(std::vector<std::array<std::uint32_t, 2>> nodes, std::vector<std::uint32_t> limbs) {
    if (nodes.size() != nodes_.size() || limbs.size() != nodes_.size())
        throw std::invalid_argument("FeatureTrack::setTopology: " + std::to_string(nodes.size()) + " node pairs and " +
                                    std::to_string(limbs.size()) + " limbs for " + std::to_string(nodes_.size()) + " bones");
    nodes_ = std::move(nodes);
    limbs_ = std::move(limbs);
}

bool FeatureTrack::related(std::size_t i, std::size_t j) const {
    if (i >= nodes_.size() || j >= nodes_.size()) return false;
    if (i == j || limbs_[i] == limbs_[j]) return true;
    for (std::uint32_t a : nodes_[i])
        for (std::uint32_t b : nodes_[j])
            if (a == b) return true;
    return false;
}

glm::vec2 FeatureTrack::toPixel(const ViewBasis& basis, const glm::vec3& p) const {
    const glm::vec3 r = p - centre_;
    const float s = static_cast<float>(cellSize_);
    return {(glm::dot(basis.right, r) / radius_ * 0.5f + 0.5f) * s, (0.5f - 0.5f * glm::dot(basis.up, r) / radius_) * s};
}

std::vector<FeatureLine> FeatureTrack::lines(int keyframe, const glm::vec3& toEye) const {
    const ViewBasis basis = viewBasis(toEye);
    std::vector<FeatureLine> out(nodes_.size());
    for (std::size_t i = 0; i < nodes_.size(); ++i)
        out[i] = {toPixel(basis, parentJoint(keyframe, i)), toPixel(basis, childJoint(keyframe, i))};
    return out;
}

std::vector<LineAttributes> FeatureTrack::attributes(int keyframe, const glm::vec3& toEye) const {
    const ViewBasis basis = viewBasis(toEye);
    const float ppm = pixelsPerMetre();
    std::vector<LineAttributes> out(nodes_.size());
    for (std::size_t i = 0; i < nodes_.size(); ++i) {
        out[i].radius = radii_[i] * ppm;
        out[i].depthP = glm::dot(basis.toEye, parentJoint(keyframe, i) - centre_) * ppm;
        out[i].depthQ = glm::dot(basis.toEye, childJoint(keyframe, i) - centre_) * ppm;
    }
    return out;
}

std::vector<float> FeatureTrack::motion(int a, int b) const {
    std::vector<float> out(nodes_.size());
    for (std::size_t i = 0; i < nodes_.size(); ++i)
        out[i] = 0.5f * (glm::length(parentJoint(a, i) - parentJoint(b, i)) + glm::length(childJoint(a, i) - childJoint(b, i)));
    return out;
}

std::size_t FeatureTrack::bytes() const {
    return joints_.size() * sizeof(glm::vec3) + radii_.size() * sizeof(float) + nodes_.size() * sizeof(nodes_[0]) +
           limbs_.size() * sizeof(std::uint32_t);
}

}  // namespace throng
