#pragma once
// Elementary functions for kernels written over their scalar type. Production instantiates the
// kernels with float and double; the tests instantiate the very same kernels with a number type
// that counts the operations it executes, to check each hand-written FMULT tally (OpTally.h).
// Each function calls std:: for built-in types and the type's own overload (found by
// argument-dependent lookup) for others, so the production code is what it was with std::.

#include <cmath>
#include <type_traits>

namespace throng::detail {

/// The scalar of world-space values (double) paired with a kernel scalar `S`. A counting type
/// specialises it, so kernels that mix float (actor space) and double (world space) count both.
template <class S>
struct WideScalar {
    using type = double;  ///< double for float and double
};
/// Shorthand for WideScalar<S>::type.
template <class S>
using Wide = typename WideScalar<S>::type;

/// `x` as a `T`: the object itself when it already is one (no copy in production), else a
/// converted copy (kernels run on a counting type convert stored float and double data so).
template <class T, class U>
inline decltype(auto) convertTo(const U& x) {
    if constexpr (std::is_same_v<T, U>) return (x);
    else return T(x);
}

/// Square root (one sqrt in the cost model).
template <class S>
inline S sqrtOf(S x) {
    using std::sqrt;
    return sqrt(x);
}
/// Absolute value (a sign-bit operation: free in the cost model).
template <class S>
inline S absOf(S x) {
    using std::abs;
    return abs(x);
}
/// Sine (transcendental functions are priced as square roots).
template <class S>
inline S sinOf(S x) {
    using std::sin;
    return sin(x);
}
/// Cosine (priced as a square root).
template <class S>
inline S cosOf(S x) {
    using std::cos;
    return cos(x);
}
/// Arc cosine (priced as a square root).
template <class S>
inline S acosOf(S x) {
    using std::acos;
    return acos(x);
}
/// Floating-point remainder (priced as a division).
template <class S>
inline S fmodOf(S x, S y) {
    using std::fmod;
    return fmod(x, y);
}
/// Whether `x` is finite (a bit test: free).
template <class S>
inline bool isFiniteOf(S x) {
    using std::isfinite;
    return isfinite(x);
}

}  // namespace throng::detail
