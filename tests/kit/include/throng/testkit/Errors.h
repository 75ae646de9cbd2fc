#pragma once
// The message a call throws, for tests that check an error names what is wrong and where.

#include <exception>
#include <string>

namespace throng::testkit {

/// What `f()` throws as `E` (what()), or "(no error)" when it returns.
template <class E = std::exception, class F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const E& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace throng::testkit
