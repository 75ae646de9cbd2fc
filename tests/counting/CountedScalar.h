#pragma once
// An operation-counting number type for the FMULT checks. The kernels of the scenegraph and the
// actors are templates over their scalar; instantiated with Counted<float> and Counted<double>,
// the very code production runs on float and double counts every operation it executes here, so a
// test can compare each hand-written THRONG_TALLY with what was executed.
//
// Counting rules (the cost model's, seed 002 §6; OpTally.h):
// - a binary +, - (and +=, -=) is one addition; *, *= one multiplication; /, /= one division,
//   whatever the operands: a multiply by a literal is executed (0.5 * x is not folded), while
//   arithmetic between constants alone is done by the compiler on plain doubles and never reaches
//   this type;
// - a comparison (<, <=, >, >=, ==, !=) is one addition, so std::min, std::max and std::clamp
//   count the comparisons they make;
// - sqrt is one square root; sin, cos, acos (the transcendental functions the kernels use) are
//   priced as one square root each, the cost model having no unit for them; fmod is one division;
// - negation, abs and conversions between float and double are free (sign-bit operations and
//   register moves), and so is isfinite (a bit test).

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "throng/actors/detail/SinCos.h"
#include "throng/scenegraph/OpTally.h"
#include "throng/scenegraph/detail/ScalarMath.h"

namespace throng::counting {

/// Operations executed by Counted values on this thread since the last ExecutedOps::reset().
struct ExecutedOps {
    /// The running tally.
    static OpTally& tally() {
        thread_local OpTally t;
        return t;
    }
    /// Clears the tally.
    static void reset() { tally() = OpTally{}; }
};

/// A float or double that counts its operations into ExecutedOps.
template <class T>
class Counted {
public:
    /// Uninitialised, like a float: glm keeps its components in unions, which need a trivial
    /// default constructor.
    Counted() = default;
    /// From a literal or stored value (free: loading data is no arithmetic).
    template <class U>
        requires std::is_arithmetic_v<U>
    constexpr Counted(U x) : v_(static_cast<T>(x)) {}  // NOLINT: implicit like a built-in promotion
    /// From the other precision (free: a conversion).
    template <class U>
        requires(!std::is_same_v<U, T>)
    constexpr explicit Counted(Counted<U> x) : v_(static_cast<T>(x.value())) {}

    /// The value.
    constexpr T value() const { return v_; }
    /// The value as a built-in number.
    constexpr explicit operator T() const { return v_; }

    /// Arithmetic, counted.
    friend Counted operator+(Counted a, Counted b) {
        ++adds();
        return Counted(a.v_ + b.v_);
    }
    friend Counted operator-(Counted a, Counted b) {
        ++adds();
        return Counted(a.v_ - b.v_);
    }
    friend Counted operator*(Counted a, Counted b) {
        ++mults();
        return Counted(a.v_ * b.v_);
    }
    friend Counted operator/(Counted a, Counted b) {
        ++divs();
        return Counted(a.v_ / b.v_);
    }
    Counted& operator+=(Counted b) { return *this = *this + b; }
    Counted& operator-=(Counted b) { return *this = *this - b; }
    Counted& operator*=(Counted b) { return *this = *this * b; }
    Counted& operator/=(Counted b) { return *this = *this / b; }
    /// Negation, free.
    friend Counted operator-(Counted a) { return Counted(-a.v_); }
    friend Counted operator+(Counted a) { return a; }

    /// Comparisons, one addition each.
    friend bool operator<(Counted a, Counted b) {
        ++adds();
        return a.v_ < b.v_;
    }
    friend bool operator<=(Counted a, Counted b) {
        ++adds();
        return a.v_ <= b.v_;
    }
    friend bool operator>(Counted a, Counted b) {
        ++adds();
        return a.v_ > b.v_;
    }
    friend bool operator>=(Counted a, Counted b) {
        ++adds();
        return a.v_ >= b.v_;
    }
    friend bool operator==(Counted a, Counted b) {
        ++adds();
        return a.v_ == b.v_;
    }
    friend bool operator!=(Counted a, Counted b) {
        ++adds();
        return a.v_ != b.v_;
    }

    /// Functions, found by argument-dependent lookup (detail::sqrtOf and friends, glm::length).
    friend Counted sqrt(Counted a) {
        ++sqrts();
        return Counted(std::sqrt(a.v_));
    }
    friend Counted sin(Counted a) {
        ++sqrts();
        return Counted(std::sin(a.v_));
    }
    friend Counted cos(Counted a) {
        ++sqrts();
        return Counted(std::cos(a.v_));
    }
    /// Both at once, with the bits of the production kernels' detail::sinCos (two priced roots).
    friend void sinCos(Counted a, Counted& sine, Counted& cosine) {
        sqrts() += 2;
        double s, c;
        throng::detail::sinCos(double(a.v_), s, c);
        sine = Counted(T(s));
        cosine = Counted(T(c));
    }
    friend Counted acos(Counted a) {
        ++sqrts();
        return Counted(std::acos(a.v_));
    }
    friend Counted fmod(Counted a, Counted b) {
        ++divs();
        return Counted(std::fmod(a.v_, b.v_));
    }
    friend Counted abs(Counted a) { return Counted(std::abs(a.v_)); }
    friend Counted fabs(Counted a) { return Counted(std::abs(a.v_)); }
    friend bool isfinite(Counted a) { return std::isfinite(a.v_); }

private:
    static std::uint64_t& adds() { return ExecutedOps::tally().adds; }
    static std::uint64_t& mults() { return ExecutedOps::tally().mults; }
    static std::uint64_t& divs() { return ExecutedOps::tally().divs; }
    static std::uint64_t& sqrts() { return ExecutedOps::tally().sqrts; }
    T v_;
};

/// Counting float (actor space).
using CFloat = Counted<float>;
/// Counting double (world space).
using CDouble = Counted<double>;

/// Operations executed by `f()` on counting values.
template <class F>
OpTally executedBy(F&& f) {
    ExecutedOps::reset();
    f();
    return ExecutedOps::tally();
}

}  // namespace throng::counting

/// glm's templates require std::numeric_limits<T>::is_iec559 of their scalar: a counting float is
/// the float it wraps.
template <class T>
struct std::numeric_limits<throng::counting::Counted<T>> : public std::numeric_limits<T> {};

/// World-space values of kernels run on a counting type count too.
template <class T>
struct throng::detail::WideScalar<throng::counting::Counted<T>> {
    using type = throng::counting::Counted<double>;  ///< counting double
};
