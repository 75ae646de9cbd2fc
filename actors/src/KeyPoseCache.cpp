#include "throng/actors/KeyPoseCache.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "throng/actors/ActorTemplate.h"
#include "throng/actors/SkeletonPose.h"

namespace throng {
namespace {

std::uint32_t countPoses(double duration, double rate) {
    const double n = std::round(duration * rate);
    return n < 1.0 ? 1u : static_cast<std::uint32_t>(std::min(n, 1.0e6));
}

// Validates before anything is built, so a bad cache leaves nothing behind.
const std::shared_ptr<const ActorTemplate>& checked(const std::shared_ptr<const ActorTemplate>& tmpl,
                                                    const KeyPoseCacheSettings& s) {
    const std::string where = "KeyPoseCache";
    if (!tmpl) throw std::invalid_argument(where + ": the template is null");
    const std::string of = where + " of template '" + tmpl->name() + "'";
    if (s.rows == 0 || s.rows > 65535) throw std::invalid_argument(of + ": rows " + std::to_string(s.rows) + " must be 1 to 65535");
    if (!(s.keyPosesPerSecond > 0.0) || !std::isfinite(s.keyPosesPerSecond))
        throw std::invalid_argument(of + ": keyPosesPerSecond must be positive and finite");
    if (s.mode != KeyPoseMode::Intermittent && s.mode != KeyPoseMode::Interpolative)
        throw std::invalid_argument(of + ": unknown mode");
    if (tmpl->clips().empty()) throw std::invalid_argument(of + ": the template has no clip to take key-poses from");
    bool skinned = false;
    for (const VaLodLevel& lv : tmpl->rootGeometry().levels()) skinned = skinned || (lv.drawable && lv.skin >= 0);
    if (!skinned) throw std::invalid_argument(of + ": the template has no skinned actor-level mesh to cache");
    for (const SkeletonNode& n : tmpl->nodes())
        if (!n.geometry.empty())
            throw std::invalid_argument(of + ": node '" + n.name +
                                        "' has rigid geometry of its own; only templates drawn by skinned meshes alone can be cached");
    return tmpl;
}

}  // namespace

KeyPoseCache::KeyPoseCache(std::shared_ptr<const ActorTemplate> tmpl, const KeyPoseCacheSettings& settings)
    : tmpl_(checked(tmpl, settings)), settings_(settings), rows_(settings.rows, 0) {
    const ActorTemplate& t = *tmpl_;
    for (std::size_t c = 0; c < t.clips().size(); ++c) {
        first_.push_back(static_cast<std::uint32_t>(clipOf_.size()));
        count_.push_back(countPoses(t.clips()[c]->duration(), settings.keyPosesPerSecond));
        clipOf_.insert(clipOf_.end(), count_.back(), static_cast<int>(c));
    }
    const std::uint32_t poses = static_cast<std::uint32_t>(clipOf_.size());
    std::size_t matrices = 0;
    for (const Skin& skin : t.skins()) {
        skinBase_.push_back(matrices);
        matrices += skin.joints.size() * poses;
    }
    palettes_.resize(matrices);
    // Every key-pose at full detail: every node active, every channel interpolated.
    std::vector<float> dofs(t.dofValueCount());
    std::vector<Affine> model(t.nodeCount());
    for (std::uint32_t p = 0; p < poses; ++p) {
        std::copy(t.restDofs().begin(), t.restDofs().end(), dofs.begin());
        t.clips()[static_cast<std::size_t>(clipOf_[p])]->sample(t, timeOf(p), true, {}, dofs);
        computeModelTransforms(t, dofs, {}, model);
        for (std::size_t s = 0; s < t.skins().size(); ++s) {
            const std::size_t n = t.skins()[s].joints.size();
            computeSkinPalette(t, t.skins()[s], model, {}, std::span<glm::mat4>(palettes_.data() + skinBase_[s] + p * n, n));
        }
    }
    rows_ = KeyPoseRows(settings.rows, poses);
}

double KeyPoseCache::timeOf(std::uint32_t pose) const {
    const int c = clipOf_[pose];
    const double duration = tmpl_->clips()[static_cast<std::size_t>(c)]->duration();
    return duration * static_cast<double>(pose - first_[static_cast<std::size_t>(c)]) / count_[static_cast<std::size_t>(c)];
}

KeyPoseSample KeyPoseCache::sample(int clip, double clipTime) const {
    if (clip < 0 || static_cast<std::size_t>(clip) >= first_.size())
        throw std::out_of_range("KeyPoseCache::sample: clip " + std::to_string(clip) + " of template '" + tmpl_->name() +
                                "' does not exist");
    const std::size_t c = static_cast<std::size_t>(clip);
    const double duration = tmpl_->clips()[c]->duration();
    const std::uint32_t n = count_[c];
    double u = duration > 0.0 && std::isfinite(clipTime) ? tmpl_->clips()[c]->localTime(clipTime, true) / duration * n : 0.0;
    if (!(u >= 0.0) || u >= n) u = 0.0;  // localTime keeps [0, duration]; duration itself is key 0 again
    KeyPoseSample s;
    if (settings_.mode == KeyPoseMode::Intermittent) {
        const std::uint32_t k = static_cast<std::uint32_t>(std::lround(u)) % n;
        s.a = s.b = first_[c] + k;
        return s;
    }
    const double k0 = std::floor(u);
    const std::uint32_t k = static_cast<std::uint32_t>(k0) % n;
    s.a = first_[c] + k;
    s.b = first_[c] + (k + 1) % n;
    s.blend = static_cast<float>(u - k0);
    if (s.a == s.b) s.blend = 0.0f;  // a clip of one key-pose
    return s;
}

std::span<const glm::mat4> KeyPoseCache::palette(std::uint32_t skin, std::uint32_t pose) const {
    if (skin >= skinBase_.size() || pose >= clipOf_.size()) return {};
    const std::size_t n = tmpl_->skins()[skin].joints.size();
    return {palettes_.data() + skinBase_[skin] + pose * n, n};
}

}  // namespace throng
