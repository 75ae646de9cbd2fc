#include "throng/scenegraph/Validation.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace throng {
namespace {

[[noreturn]] void fail(std::string_view where, std::string_view object, std::string_view name,
                       std::string_view component, double value) {
    std::ostringstream msg;
    msg << errorContext(where, object) << ": argument '" << name << "'";
    if (!component.empty()) msg << " has a non-finite component " << component << " = " << value;
    else msg << " is not finite (" << value << ")";
    throw std::invalid_argument(msg.str());
}

}  // namespace

std::string errorContext(std::string_view where, std::string_view object) {
    std::string s(where);
    if (!object.empty()) {
        s += " on '";
        s += object;
        s += "'";
    }
    return s;
}

void requireFinite(double value, std::string_view where, std::string_view name,
                   std::string_view object) {
    if (!std::isfinite(value)) fail(where, object, name, {}, value);
}

void requireFinite(const Vec3& v, std::string_view where, std::string_view name,
                   std::string_view object) {
    static constexpr const char* kNames[] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(v[i])) fail(where, object, name, kNames[i], v[i]);
}

void requireFinite(const Vec4& v, std::string_view where, std::string_view name,
                   std::string_view object) {
    static constexpr const char* kNames[] = {"x", "y", "z", "w"};
    for (int i = 0; i < 4; ++i)
        if (!std::isfinite(v[i])) fail(where, object, name, kNames[i], v[i]);
}

void requireFinite(const Mat4& m, std::string_view where, std::string_view name,
                   std::string_view object) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) {
                const std::string component =
                    "[column " + std::to_string(c) + "][row " + std::to_string(r) + "]";
                fail(where, object, name, component, m[c][r]);
            }
}

void requireFinite(const Quat& q, std::string_view where, std::string_view name,
                   std::string_view object) {
    static constexpr const char* kNames[] = {"x", "y", "z", "w"};
    for (int i = 0; i < 4; ++i)
        if (!std::isfinite(q[i])) fail(where, object, name, kNames[i], q[i]);
}

}  // namespace throng
