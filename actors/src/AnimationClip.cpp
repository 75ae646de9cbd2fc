#include "throng/actors/AnimationClip.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "SpanChecks.h"
#include "throng/actors/ActorTemplate.h"
#include "throng/actors/detail/ClipKernels.h"

namespace throng {
namespace {

// Orders key-time arrays lexicographically, so that equal ones meet in a map.
struct TimesLess {
    bool operator()(std::span<const float> a, std::span<const float> b) const {
        return std::lexicographical_compare(a.begin(), a.end(), b.begin(), b.end());
    }
};

std::string channelName(const std::string& clip, std::size_t i) {
    return "clip '" + clip + "', channel " + std::to_string(i);
}

}  // namespace

AnimationClip::AnimationClip(std::string name, std::vector<ClipChannel> channels)
    : name_(std::move(name)), channels_(std::move(channels)) {
    for (std::size_t i = 0; i < channels_.size(); ++i) {
        const ClipChannel& c = channels_[i];
        if (c.times.empty()) throw std::invalid_argument(channelName(name_, i) + ": has no keys");
        for (std::size_t k = 0; k < c.times.size(); ++k) {
            if (!std::isfinite(c.times[k]) || c.times[k] < 0.0f)
                throw std::invalid_argument(channelName(name_, i) + ": key " + std::to_string(k) +
                                            " has an invalid time (" + std::to_string(c.times[k]) + ")");
            if (k > 0 && !(c.times[k] > c.times[k - 1]))
                throw std::invalid_argument(channelName(name_, i) + ": key times are not strictly increasing at key " +
                                            std::to_string(k));
        }
        const std::size_t perKey = c.values.size() / c.times.size();
        if (perKey == 0 || perKey * c.times.size() != c.values.size())
            throw std::invalid_argument(channelName(name_, i) + ": " + std::to_string(c.values.size()) +
                                        " values do not divide into " + std::to_string(c.times.size()) + " keys");
        for (float v : c.values)
            if (!std::isfinite(v)) throw std::invalid_argument(channelName(name_, i) + ": has a non-finite value");
        duration_ = std::max(duration_, static_cast<double>(c.times.back()));
    }
    // Channels with equal key times, found through a map from times to the first such channel.
    std::map<std::span<const float>, std::uint32_t, TimesLess> first;
    timeSources_.reserve(channels_.size());
    for (std::size_t i = 0; i < channels_.size(); ++i)
        timeSources_.push_back(first.try_emplace(std::span<const float>(channels_[i].times), static_cast<std::uint32_t>(i)).first->second);
}

double AnimationClip::localTime(double t, bool loop) const { return detail::clipLocalTime(duration_, t, loop, nullptr); }

std::size_t AnimationClip::sample(const ActorTemplate& tmpl, double t, bool loop, std::span<const std::uint8_t> active,
                                  std::span<float> dofs, OpTally* ops, bool holdKeys) const {
    detail::requireFlagsOrNone(active.size(), tmpl.nodeCount(), "AnimationClip::sample", tmpl);
    detail::requireEntries(dofs.size(), tmpl.dofValueCount(), "AnimationClip::sample", "dofs", tmpl, "every DOF value");
    return detail::sampleClip(*this, tmpl, t, loop, active, dofs, ops, holdKeys);
}

RootPose AnimationClip::sampleRoot(double t, bool loop, OpTally* ops, bool holdKeys) const {
    return detail::sampleClipRoot<float>(*this, t, loop, ops, holdKeys);
}

}  // namespace throng
