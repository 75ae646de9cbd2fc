#include "throng/sim/BehaviourLayer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "throng/actors/ActorTemplate.h"

namespace throng::sim {

BehaviourLayer::BehaviourLayer(std::shared_ptr<Behaviour> base, const char* who) : base_(std::move(base)) {
    if (!base_) throw std::invalid_argument(std::string(who) + ": argument 'base' is null");
}

std::vector<double> BehaviourLayer::mergeBands(const std::vector<std::vector<double>>& own) {
    ends_.assign(base_->levelEnds().begin(), base_->levelEnds().end());
    for (const auto& ends : own) ends_.insert(ends_.end(), ends.begin(), ends.end());
    std::sort(ends_.begin(), ends_.end());
    ends_.erase(std::unique(ends_.begin(), ends_.end()), ends_.end());
    std::vector<double> inside;
    baseLevel_.clear();
    for (std::size_t i = 0; i <= ends_.size(); ++i) {
        const double lo = i == 0 ? 0.0 : ends_[i - 1];
        const double hi = i < ends_.size() ? ends_[i] : std::numeric_limits<double>::infinity();
        const double mid = std::isinf(hi) ? (std::isinf(lo) ? lo : 2.0 * lo + 1.0) : 0.5 * (lo + hi);
        baseLevel_.push_back(base_->levelFor(mid));
        inside.push_back(mid);
    }
    return inside;
}

void BehaviourLayer::restNode(const ActorTemplate& tmpl, int node, std::span<float> dofs) {
    if (node < 0) return;
    const std::size_t first = tmpl.dofOffset(std::size_t(node));
    const std::size_t end = std::size_t(node) + 1 < tmpl.nodeCount() ? tmpl.dofOffset(std::size_t(node) + 1) : tmpl.morphWeightOffset();
    std::copy(tmpl.restDofs().begin() + std::ptrdiff_t(first), tmpl.restDofs().begin() + std::ptrdiff_t(end), dofs.begin() + std::ptrdiff_t(first));
}

}  // namespace throng::sim
