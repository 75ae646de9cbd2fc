#pragma once
// Argument checks for the public API: NaN and Inf are rejected at the boundary with an error that
// names the function, the object (when it has a name) and the argument, so bad values never reach
// the traversals. Messages are only built on failure: checks cost a few compares on hot paths.

#include <string>
#include <string_view>

#include "throng/scenegraph/Math.h"

namespace throng {

/// Throws std::invalid_argument "<where> on '<object>': argument '<name>' is not finite (...)"
/// unless `value` is finite (the object part is left out when `object` is empty).
void requireFinite(double value, std::string_view where, std::string_view name,
                   std::string_view object = {});
/// Throws std::invalid_argument naming the component unless every component of `value` is finite.
void requireFinite(const Vec3& value, std::string_view where, std::string_view name,
                   std::string_view object = {});
/// Throws std::invalid_argument naming the component unless every component of `value` is finite.
void requireFinite(const Vec4& value, std::string_view where, std::string_view name,
                   std::string_view object = {});
/// Throws std::invalid_argument naming the element unless every element of `value` is finite.
void requireFinite(const Mat4& value, std::string_view where, std::string_view name,
                   std::string_view object = {});
/// Throws std::invalid_argument naming the component unless every component of `value` is finite.
void requireFinite(const Quat& value, std::string_view where, std::string_view name,
                   std::string_view object = {});

/// Builds the "<where> on '<object>'" prefix of an error message.
std::string errorContext(std::string_view where, std::string_view object);

}  // namespace throng
