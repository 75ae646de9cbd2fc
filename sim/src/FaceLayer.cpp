#include "throng/sim/FaceLayer.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <glm/gtc/quaternion.hpp>

#include "throng/actors/ActorTemplate.h"
#include "throng/sim/CounterRng.h"

namespace throng::sim {
namespace {

std::string lower(const std::string& s) {
    std::string out(s);
    for (char& c : out) c = char(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

bool hasAny(const std::string& name, std::initializer_list<const char*> words) {
    const std::string l = lower(name);
    for (const char* w : words)
        if (l.find(w) != std::string::npos) return true;
    return false;
}

void checkLevels(const std::vector<double>& levels, const char* what) {
    for (std::size_t i = 0; i < levels.size(); ++i)
        if (!(levels[i] > 0.0) || !std::isfinite(levels[i]) || (i > 0 && levels[i] <= levels[i - 1]))
            throw std::invalid_argument(std::string("FaceLayer: ") + what + " level ends must be positive, finite and increasing");
}

void checkPositive(double v, const char* what) {
    if (!(v > 0.0) || !std::isfinite(v)) throw std::invalid_argument(std::string("FaceLayer: ") + what + " must be positive and finite");
}

// The band of `distance`'s middle among `ends` (ends.size() beyond the last).
int bandOf(const std::vector<double>& ends, double mid) {
    int l = 0;
    while (l < int(ends.size()) && !(mid < ends[std::size_t(l)])) ++l;
    return l;
}

// Counters of an actor's stream, one block per timeline (segment numbers times 8 plus these).
constexpr std::uint64_t kExpressionPick = 0, kExpressionLength = 1, kExpressionPhase = 2, kBlinkLength = 3, kBlinkPhase = 4;
constexpr std::uint64_t kTurnPhrase = 5, kTurnPhase = 6, kTurnFirst = 7;

// How open the mouth is for a letter: vowels open it, lips closing on m, b and p, spaces and
// punctuation close it, other consonants leave it ajar.
double letterOpen(char c) {
    switch (std::tolower(static_cast<unsigned char>(c))) {
        case 'a': case 'o': return 1.0;
        case 'e': case 'i': case 'u': case 'y': return 0.6;
        case 'm': case 'b': case 'p': return 0.0;
        default: return std::isalpha(static_cast<unsigned char>(c)) ? 0.35 : 0.0;
    }
}

}  // namespace

FaceLayer::FaceLayer(std::shared_ptr<Behaviour> base, Settings settings, EffectCounters* counters)
    : BehaviourLayer(std::move(base), "FaceLayer"), settings_(std::move(settings)), counters_(counters) {
    const Settings& s = settings_;
    checkLevels(s.faceLevels, "face");
    checkLevels(s.blinkLevels, "blink");
    checkLevels(s.phraseLevels, "phrase");
    if (!(s.transition >= 0.0) || !std::isfinite(s.transition)) throw std::invalid_argument("FaceLayer: transition must be >= 0 and finite");
    for (const Expression& e : s.expressions) {
        checkPositive(e.duration, "an expression's duration");
        for (const auto& [name, w] : e.weights)
            if (!std::isfinite(w)) throw std::invalid_argument("FaceLayer: expression '" + e.name + "': weight of '" + name + "' is not finite");
    }
    checkPositive(s.blinkMean, "blink mean");
    checkPositive(s.blinkDuration, "blink duration");
    if (!(s.blinkSpread >= 0.0) || !(s.blinkSpread < s.blinkMean))
        throw std::invalid_argument("FaceLayer: blink spread must be >= 0 and below the mean");
    checkPositive(s.lettersPerSecond, "letters per second");
    if (!(s.pause >= 0.0) || !std::isfinite(s.pause)) throw std::invalid_argument("FaceLayer: pause must be >= 0 and finite");
    // The base's bands and the declared effects' bands, merged; each merged band's level of each.
    const std::vector<double> none;
    for (const double mid : mergeBands({s.face ? s.faceLevels : none, s.blink ? s.blinkLevels : none, s.phrase ? s.phraseLevels : none})) {
        faceLevel_.push_back(s.face ? bandOf(s.faceLevels, mid) : int(s.faceLevels.size()));
        blinkLevel_.push_back(s.blink ? bandOf(s.blinkLevels, mid) : int(s.blinkLevels.size()));
        phraseLevel_.push_back(s.phrase ? bandOf(s.phraseLevels, mid) : int(s.phraseLevels.size()));
    }
    if (counters_) {
        if (s.face) counters_->constructed("face");
        if (s.blink) counters_->constructed("blink");
        if (s.phrase) counters_->constructed("phrase");
    }
}

const FaceLayer::FaceRig& FaceLayer::rigOf(const ActorTemplate& tmpl) {
    if (const auto it = rigs_.find(&tmpl); it != rigs_.end()) return *it->second;
    auto rig = std::make_unique<FaceRig>();
    for (const Expression& e : settings_.expressions) {
        auto& list = rig->expressions.emplace_back();
        for (const auto& [name, w] : e.weights)
            if (const int c = tmpl.findMorphChannel(name); c >= 0) list.emplace_back(std::uint32_t(c), w);
        rig->durations.push_back(e.duration);
    }
    const auto channels = tmpl.morphChannels();
    for (std::size_t c = 0; c < channels.size() && rig->blinkChannel < 0; ++c)
        if (hasAny(channels[c], {"blink", "eyelid", "eyesclosed", "eyes closed", "eyeclose"})) rig->blinkChannel = int(c);
    if (rig->blinkChannel < 0)
        for (std::size_t i = 0; i < tmpl.nodeCount(); ++i) {
            const SkeletonNode& n = tmpl.nodes()[i];
            if (!hasAny(n.name, {"eye"}) || hasAny(n.name, {"brow", "lash"})) continue;
            for (const Dof& d : n.dofs)
                if (d.kind == DofKind::Scale) rig->eyeJoints.push_back(int(i));
        }
    for (const std::string& name : settings_.mouthTargets)
        if (rig->mouthChannel < 0) rig->mouthChannel = tmpl.findMorphChannel(name);
    for (std::size_t c = 0; c < channels.size() && rig->mouthChannel < 0; ++c)
        if (hasAny(channels[c], {"mouth", "jawopen", "jaw_open", "viseme", "aa"})) rig->mouthChannel = int(c);
    if (rig->mouthChannel < 0)
        for (std::size_t i = 0; i < tmpl.nodeCount() && rig->jawJoint < 0; ++i)
            if (hasAny(tmpl.nodes()[i].name, {"jaw"}))
                for (const Dof& d : tmpl.nodes()[i].dofs)
                    if (d.kind == DofKind::Orientation || d.kind == DofKind::RotateAxis) rig->jawJoint = int(i);
    if (settings_.expressions.empty() && settings_.face) {  // declared without a set: the template's own
        rig->expressions.emplace_back();
        rig->durations.push_back(4.0);
        for (std::size_t c = 0; c < channels.size(); ++c)
            if (int(c) != rig->blinkChannel && int(c) != rig->mouthChannel) {
                rig->expressions.push_back({{std::uint32_t(c), 1.0f}});
                rig->durations.push_back(2.5);
            }
    }
    // A template none of whose morph channels an expression names has no face to move.
    bool anyChannel = false;
    for (const auto& list : rig->expressions) anyChannel = anyChannel || !list.empty();
    if (!anyChannel) rig->expressions.clear(), rig->durations.clear();
    return *rigs_.emplace(&tmpl, std::move(rig)).first->second;
}

std::uint32_t FaceLayer::wrap(std::uint32_t baseSlot, const std::shared_ptr<const ActorTemplate>& tmpl, std::uint64_t stream,
                              std::uint64_t group, std::uint32_t member, std::uint32_t groupSize) {
    if (!tmpl) throw std::invalid_argument("FaceLayer::wrap: argument 'tmpl' is null");
    if (groupSize == 0 || member >= groupSize) throw std::invalid_argument("FaceLayer::wrap: member must be below a positive group size");
    if (state_.size() <= baseSlot) state_.resize(std::size_t(baseSlot) + 1);
    State& s = state_[baseSlot];
    s.rig = &rigOf(*tmpl);
    s.stream = stream;
    s.group = group;
    s.member = member;
    s.groupSize = groupSize;
    return baseSlot;
}

template <class Length>
void FaceLayer::walk(Clock& clock, double time, Length length) {
    if (!clock.begun || time < clock.start) {  // first use, or time went back: from the beginning
        clock = Clock{0, 0.0, length(0), true};
    }
    // The same additions in the same order whenever the walk is made: exact catch-up.
    while (time >= clock.start + clock.length) {
        clock.start += clock.length;
        ++clock.index;
        clock.length = length(clock.index);
    }
}

int FaceLayer::expressionOf(const State& s, std::uint64_t index) const {
    const CounterRng rng(settings_.seed, s.stream);
    return int(rng.below(index * 8 + kExpressionPick, s.rig->expressions.size()));
}

void FaceLayer::writeExpression(State& s, double time, bool strongestOnly, std::span<float> weights) {
    const CounterRng rng(settings_.seed, s.stream);
    walk(s.expression, time, [&](std::uint64_t index) {
        const double held = s.rig->durations[std::size_t(expressionOf(s, index))] * rng.uniform(index * 8 + kExpressionLength, 0.8, 1.2);
        // The first one is cut at a random point: actors do not change expression in step.
        return index == 0 ? std::max(1e-3, held * rng.uniform(kExpressionPhase)) : held;
    });
    const auto& now = s.rig->expressions[std::size_t(expressionOf(s, s.expression.index))];
    const auto& before = s.rig->expressions[std::size_t(expressionOf(s, s.expression.index == 0 ? 0 : s.expression.index - 1))];
    double blend = 1.0;
    if (s.expression.index > 0 && settings_.transition > 0.0) {
        const double u = std::clamp((time - s.expression.start) / settings_.transition, 0.0, 1.0);
        blend = u * u * (3.0 - 2.0 * u);  // smoothstep: no step in weight nor in its rate
    }
    // Every channel some expression names belongs to the face: zero unless the two blended name it.
    for (const auto& list : s.rig->expressions)
        for (const auto& [c, w] : list) weights[c] = 0.0f;
    for (const auto& [c, w] : before) weights[c] += float((1.0 - blend) * w);
    for (const auto& [c, w] : now) weights[c] += float(blend * w);
    if (strongestOnly) {  // the far band: one target read instead of several
        int best = -1;
        for (const auto& list : s.rig->expressions)
            for (const auto& [c, w] : list)
                if (best < 0 || std::abs(weights[c]) > std::abs(weights[std::size_t(best)])) best = int(c);
        for (const auto& list : s.rig->expressions)
            for (const auto& [c, w] : list)
                if (int(c) != best) weights[c] = 0.0f;
    }
}

std::vector<float> FaceLayer::expressionAt(std::uint32_t slot, double time) {
    State& s = state_.at(slot);
    std::vector<float> weights;
    std::size_t channels = 0;
    for (const auto& list : s.rig->expressions)
        for (const auto& [c, w] : list) channels = std::max<std::size_t>(channels, c + 1);
    weights.assign(channels, 0.0f);
    if (!s.rig->expressions.empty()) writeExpression(s, time, false, weights);
    return weights;
}

double FaceLayer::blinkAt(std::uint32_t slot, double time) {
    State& s = state_.at(slot);
    const CounterRng rng(settings_.seed, s.stream);
    const double d = settings_.blinkDuration;
    walk(s.blink, time, [&](std::uint64_t index) {
        const double gap = std::max(d, settings_.blinkMean + settings_.blinkSpread * (2.0 * rng.uniform(index * 8 + kBlinkLength) - 1.0));
        return index == 0 ? d + (gap - d) * rng.uniform(kBlinkPhase) : gap;
    });
    // Each interval ends with a blink: half a sine over its duration, 0 at both ends.
    const double into = time - (s.blink.start + s.blink.length - d);
    return into > 0.0 ? std::sin(std::numbers::pi * std::min(into / d, 1.0)) : 0.0;
}

int FaceLayer::phraseOf(const State& s, std::uint64_t index) const {
    const CounterRng rng(settings_.seed ^ 0x7A1C5ull, s.group);
    return int(rng.below(index * 8 + kTurnPhrase, settings_.phrases.size()));
}

double FaceLayer::turnLength(const State& s, std::uint64_t index) const {
    const double said = double(settings_.phrases[std::size_t(phraseOf(s, index))].size()) / settings_.lettersPerSecond;
    const double length = std::max(said + settings_.pause, 1e-3);
    if (index > 0) return length;
    const CounterRng rng(settings_.seed ^ 0x7A1C5ull, s.group);
    return std::max(1e-3, length * rng.uniform(kTurnPhase));
}

std::uint32_t FaceLayer::speakerOf(const State& s, std::uint64_t index) const {
    // Members take turns in order, from a member drawn per group.
    const CounterRng rng(settings_.seed ^ 0x7A1C5ull, s.group);
    return std::uint32_t((rng.below(kTurnFirst, s.groupSize) + index) % s.groupSize);
}

FaceLayer::Speech FaceLayer::speechAt(std::uint32_t slot, double time) {
    State& s = state_.at(slot);
    if (settings_.phrases.empty()) return {};
    walk(s.turn, time, [&](std::uint64_t index) { return turnLength(s, index); });
    if (s.turn.index == 0 || speakerOf(s, s.turn.index) != s.member) return {};  // turn 0 is the group's phase
    const int phrase = phraseOf(s, s.turn.index);
    const double said = double(settings_.phrases[std::size_t(phrase)].size()) / settings_.lettersPerSecond;
    const double into = time - s.turn.start;
    if (into >= said) return {};
    return {phrase, std::clamp(into / said, 0.0, 1.0)};
}

double FaceLayer::mouthOpen(const std::string& phrase, double progress) const {
    if (phrase.empty()) return 0.0;
    // Each letter's shape at its middle, interpolated between letters: never a step.
    const double x = progress * double(phrase.size()) - 0.5;
    const auto i = std::size_t(std::clamp(std::floor(x), 0.0, double(phrase.size() - 1)));
    const std::size_t j = std::min(i + 1, phrase.size() - 1);
    const double f = std::clamp(x - double(i), 0.0, 1.0);
    return (1.0 - f) * letterOpen(phrase[i]) + f * letterOpen(phrase[j]);
}

void FaceLayer::pose(std::uint32_t slot, double time, int level, const ActorTemplate& tmpl, std::span<const std::uint8_t> active,
                     std::span<float> dofs, OpTally* ops) {
    if (slot < state_.size() && state_[slot].rig) {  // last frame's face does not carry over
        const FaceRig& rig = *state_[slot].rig;
        const auto rest = tmpl.restDofs().subspan(tmpl.morphWeightOffset());
        std::copy(rest.begin(), rest.end(), dofs.begin() + std::ptrdiff_t(tmpl.morphWeightOffset()));
        for (int j : rig.eyeJoints) restNode(tmpl, j, dofs);
        restNode(tmpl, rig.jawJoint, dofs);
    }
    base_->pose(slot, time, baseLevel(level), tmpl, active, dofs, ops);
    if (slot >= state_.size() || !state_[slot].rig) return;
    State& s = state_[slot];
    const FaceRig& rig = *s.rig;
    const int fl = faceLevel_[std::size_t(level)], bl = blinkLevel_[std::size_t(level)], pl = phraseLevel_[std::size_t(level)];
    const bool face = fl < int(settings_.faceLevels.size()) && !rig.expressions.empty();
    const bool blink = bl < int(settings_.blinkLevels.size()) && (rig.blinkChannel >= 0 || !rig.eyeJoints.empty());
    const bool phrase = pl < int(settings_.phraseLevels.size()) && !settings_.phrases.empty() && (rig.mouthChannel >= 0 || rig.jawJoint >= 0);
    if (!face && !blink && !phrase) return;  // beyond every band: nothing is evaluated
    const auto started = std::chrono::steady_clock::now();
    const std::span<float> weights = dofs.subspan(tmpl.morphWeightOffset(), tmpl.morphChannels().size());
    if (face) {
        writeExpression(s, time, fl > 0, weights);
        faceTicks_.fetch_add(1, std::memory_order_relaxed);
    }
    if (blink) {
        const double w = blinkAt(slot, time);
        if (rig.blinkChannel >= 0) {
            weights[std::size_t(rig.blinkChannel)] = float(w);
        } else {
            for (int j : rig.eyeJoints) {
                if (!active.empty() && !active[std::size_t(j)]) continue;
                const SkeletonNode& n = tmpl.nodes()[std::size_t(j)];
                for (std::size_t d = 0; d < n.dofs.size(); ++d)
                    if (n.dofs[d].kind == DofKind::Scale) dofs[tmpl.dofValueOffset(std::size_t(j), d) + 1] *= float(1.0 - 0.9 * w);
            }
        }
        blinkTicks_.fetch_add(1, std::memory_order_relaxed);
    }
    if (phrase) {
        const Speech speech = speechAt(slot, time);
        const double open = speech.phrase >= 0 ? mouthOpen(settings_.phrases[std::size_t(speech.phrase)], speech.progress) : 0.0;
        if (rig.mouthChannel >= 0) {
            weights[std::size_t(rig.mouthChannel)] = std::max(weights[std::size_t(rig.mouthChannel)], float(open));
        } else if (open > 0.0 && (active.empty() || active[std::size_t(rig.jawJoint)])) {
            const SkeletonNode& n = tmpl.nodes()[std::size_t(rig.jawJoint)];
            for (std::size_t d = 0; d < n.dofs.size(); ++d) {
                float* v = dofs.data() + tmpl.dofValueOffset(std::size_t(rig.jawJoint), d);
                if (n.dofs[d].kind == DofKind::Orientation) {
                    const glm::quat q = glm::quat(v[3], v[0], v[1], v[2]) * glm::angleAxis(float(0.35 * open), glm::vec3(1, 0, 0));
                    v[0] = q.x, v[1] = q.y, v[2] = q.z, v[3] = q.w;
                    break;
                }
                if (n.dofs[d].kind == DofKind::RotateAxis) {
                    *v = std::clamp(*v + float(0.35 * open), n.dofs[d].min, n.dofs[d].max);
                    break;
                }
            }
        }
        phraseTicks_.fetch_add(1, std::memory_order_relaxed);
    }
    THRONG_TALLY(ops, 20, 20, 0, 4);
    nanoseconds_.fetch_add(std::uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - started).count()),
                           std::memory_order_relaxed);
}

void FaceLayer::advance(const FrameContext& context) {
    base_->advance(context);  // the layer owns its base: the crowd only knows the layer
    flushCounts();
}

double FaceLayer::flushCounts() {
    const std::uint64_t face = faceTicks_.exchange(0), blink = blinkTicks_.exchange(0), phrase = phraseTicks_.exchange(0);
    if (counters_) {
        if (settings_.face) counters_->ticked("face", face);
        if (settings_.blink) counters_->ticked("blink", blink);
        if (settings_.phrase) counters_->ticked("phrase", phrase);
    }
    seconds_ += double(nanoseconds_.exchange(0)) * 1e-9;
    return seconds_;
}

}  // namespace throng::sim
