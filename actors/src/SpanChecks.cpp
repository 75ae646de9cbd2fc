#include "SpanChecks.h"

#include <stdexcept>
#include <string>

#include "throng/actors/ActorTemplate.h"

namespace throng::detail {

void throwSpanTooShort(const char* where, const char* name, std::size_t got, std::size_t want, const ActorTemplate& tmpl,
                       const char* what) {
    throw std::invalid_argument(std::string(where) + ": argument '" + name + "' holds " + std::to_string(got) +
                                " entries; template '" + tmpl.name() + "' needs " + std::to_string(want) + " (" + what + ")");
}

}  // namespace throng::detail
