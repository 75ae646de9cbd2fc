#pragma once
// Faces (seed 002 §7.1): a layer over any behaviour that gives near actors facial expressions,
// blinks and spoken phrases, each an effect a scene declares ("face", "blink", "phrase") with its
// own distance bands (behavioural LOD: beyond its last band an effect is not evaluated at all, and
// the actor keeps the neutral face its base behaviour gives).
//
//   * Expression: a timeline of the scene's expressions (each a set of morph weights held for its
//     duration), the next one drawn from the actor's own random stream, blended over a transition.
//   * Blink: blinks at random intervals (mean and spread), each a smooth weight curve (half a sine,
//     never a step) on an eyelid morph target, or else a squash of eye joints that have a scale DOF.
//   * Phrase: actors of a group take turns saying one of the scene's phrases: a timed sequence of
//     mouth shapes (a viseme per letter, interpolated) on a mouth morph target or a jaw joint, and
//     a caption the application shows above near speakers (speech()).
//
// Every timeline is a deterministic sequence of segments drawn from (seed, actor stream, segment
// number): an actor evaluated again after a time out of its band walks the segments it missed and
// resumes exactly where it would be had it been evaluated throughout (no drift, no pop), and what
// it shows never depends on the view or on the order actors are posed.

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "throng/sim/BehaviourLayer.h"
#include "throng/sim/EffectCounters.h"

namespace throng::sim {

/// Expression, blink and phrase control over a base behaviour.
class FaceLayer : public BehaviourLayer {
public:
    /// One expression: morph weights by channel name, held for `duration` seconds.
    struct Expression {
        std::string name;                       ///< for captions and statistics
        std::map<std::string, float> weights;   ///< morph channel name -> weight (others 0)
        double duration = 3.0;                  ///< seconds held (before the next transition)
    };
    /// What the scene declares.
    struct Settings {
        bool face = false;                      ///< expressions declared
        std::vector<double> faceLevels{15.0};   ///< expression bands: every weight, then the strongest only
        std::vector<Expression> expressions;    ///< the set drawn from (empty: one per morph target, and neutral)
        double transition = 0.4;                ///< seconds to blend from one expression to the next
        bool blink = false;                     ///< blinking declared
        std::vector<double> blinkLevels{10.0};  ///< blink bands
        double blinkMean = 4.0;                 ///< mean seconds between blinks
        double blinkSpread = 2.0;               ///< intervals uniform in mean +- spread
        double blinkDuration = 0.15;            ///< seconds from open to closed to open
        bool phrase = false;                    ///< phrases declared
        std::vector<double> phraseLevels{12.0, 25.0};  ///< caption and mouth, then the mouth only
        std::vector<std::string> phrases;       ///< what people say
        double lettersPerSecond = 14.0;         ///< speaking rate
        double pause = 1.5;                     ///< seconds between two turns of a group
        std::vector<std::string> mouthTargets;  ///< morph channels tried for the mouth before the usual names
        std::uint64_t seed = 1;                 ///< who says what, and when
    };
    /// What an actor is saying at a time.
    struct Speech {
        int phrase = -1;        ///< index into Settings::phrases, or -1: silent
        double progress = 0.0;  ///< share of the phrase said so far, [0, 1]
    };
    /// What one actor's face does with its template (found once per template).
    struct FaceRig {
        /// Per expression: (morph channel, weight). Without expressions in the settings: the
        /// neutral face, then each morph channel (but the eyelid's and the mouth's) at weight 1.
        std::vector<std::vector<std::pair<std::uint32_t, float>>> expressions;
        std::vector<double> durations;    ///< per expression: seconds held
        int blinkChannel = -1;            ///< eyelid morph channel, or -1
        std::vector<int> eyeJoints;       ///< else: eye joints with a Scale DOF (squashed in y)
        int mouthChannel = -1;            ///< mouth morph channel, or -1
        int jawJoint = -1;                ///< else: a jaw joint with an orientation or axis DOF
    };

    /// A face layer over `base`, counting into `counters` (may be null). Throws
    /// std::invalid_argument naming the setting when bands are not positive and increasing, a
    /// duration or rate is not positive, or a weight is not finite.
    FaceLayer(std::shared_ptr<Behaviour> base, Settings settings, EffectCounters* counters = nullptr);

    /// Gives base slot `baseSlot` (an actor of template `tmpl`, with random stream `stream`, in
    /// conversation group `group` of `groupSize` members, being member `member`) a face; returns
    /// the layer's slot (the same number).
    std::uint32_t wrap(std::uint32_t baseSlot, const std::shared_ptr<const ActorTemplate>& tmpl, std::uint64_t stream,
                       std::uint64_t group, std::uint32_t member, std::uint32_t groupSize);
    /// The rig found on `tmpl` (what each effect can move on it).
    const FaceRig& rigOf(const ActorTemplate& tmpl);

    /// The expression weights (per morph channel of the slot's template) at `time`, whatever the
    /// distance: what pose() writes within the face band. For tests and tools.
    std::vector<float> expressionAt(std::uint32_t slot, double time);
    /// The blink weight (0 open, 1 closed) of `slot` at `time`.
    double blinkAt(std::uint32_t slot, double time);
    /// What `slot` is saying at `time`.
    Speech speechAt(std::uint32_t slot, double time);
    /// The scene's phrases.
    const std::vector<std::string>& phrases() const { return settings_.phrases; }
    /// The effects' bands, merged with the base's (the layer's levels).
    const Settings& settings() const { return settings_; }
    /// Whether the phrase effect shows a caption at merged level `level` (its first band).
    bool captionAt(int level) const { return phraseLevel_[std::size_t(level)] == 0; }

    /// Hands the evaluations counted since the last call to the EffectCounters ("face", "blink",
    /// "phrase": one tick per actor evaluated) and returns the seconds spent evaluating them
    /// (advance() calls it; call it once more after the last frame).
    double flushCounts();

    void advance(const FrameContext& context) override;
    void pose(std::uint32_t slot, double time, int level, const ActorTemplate& tmpl,
              std::span<const std::uint8_t> active, std::span<float> dofs, OpTally* ops) override;
    std::size_t bytesPerSlot() const override { return base_->bytesPerSlot() + sizeof(State); }

private:
    // A timeline's place: segment `index` started at `start` (seconds) and lasts `length`.
    struct Clock {
        std::uint64_t index = 0;
        double start = 0.0, length = 0.0;
        bool begun = false;
    };
    struct State {
        const FaceRig* rig = nullptr;
        std::uint64_t stream = 0, group = 0;
        std::uint32_t member = 0, groupSize = 1;
        Clock expression, blink, turn;
    };
    // Moves `clock` to the segment holding `time`; `length(index)` gives each segment's length.
    template <class Length>
    static void walk(Clock& clock, double time, Length length);
    int expressionOf(const State& s, std::uint64_t index) const;
    double turnLength(const State& s, std::uint64_t index) const;
    int phraseOf(const State& s, std::uint64_t index) const;
    std::uint32_t speakerOf(const State& s, std::uint64_t index) const;
    void writeExpression(State& s, double time, bool strongestOnly, std::span<float> weights);
    double mouthOpen(const std::string& phrase, double progress) const;

    Settings settings_;
    EffectCounters* counters_;
    std::vector<int> faceLevel_, blinkLevel_, phraseLevel_;  // per merged level
    std::vector<State> state_;
    std::map<const ActorTemplate*, std::unique_ptr<FaceRig>> rigs_;
    // Counted by pose() (called in parallel), handed over by flushCounts().
    std::atomic<std::uint64_t> faceTicks_{0}, blinkTicks_{0}, phraseTicks_{0}, nanoseconds_{0};
    double seconds_ = 0.0;
};

}  // namespace throng::sim
