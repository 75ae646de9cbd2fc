#pragma once
// Internal to actors: the size checks of the pose jobs' caller-owned spans (as ozz-animation's jobs
// validate theirs). A check is one comparison; the message, naming the job, the argument, the
// template and what the span must hold, is built only when it fails.

#include <cstddef>

namespace throng {

class ActorTemplate;

namespace detail {

/// Throws std::invalid_argument: `where`'s argument `name` holds `got` entries, template `tmpl`
/// needs at least `want` (`what` says what they are).
[[noreturn]] void throwSpanTooShort(const char* where, const char* name, std::size_t got, std::size_t want,
                                    const ActorTemplate& tmpl, const char* what);

/// Requires `got` >= `want` entries in argument `name` of `where`.
inline void requireEntries(std::size_t got, std::size_t want, const char* where, const char* name, const ActorTemplate& tmpl,
                           const char* what) {
    if (got < want) [[unlikely]]
        throwSpanTooShort(where, name, got, want, tmpl, what);
}

/// Requires the `active` flags of `where` to be empty (every node) or one per node.
inline void requireFlagsOrNone(std::size_t got, std::size_t nodes, const char* where, const ActorTemplate& tmpl) {
    if (got != 0 && got < nodes) [[unlikely]]
        throwSpanTooShort(where, "active", got, nodes, tmpl, "one flag per node, or none for every node");
}

}  // namespace detail
}  // namespace throng
