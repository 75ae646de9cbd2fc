#pragma once
// Elementary floating-point operations performed by a piece of code, and their FMULT cost with the
// unit costs of the cost model (seed 002 §6): mult 1, add 1, div 5, sqrt 7, GPU 4x4 product 10.

#include <cstdint>

namespace throng {

/// FMULT unit costs of the cost model.
struct FmultCost {
    static constexpr std::uint64_t kMult = 1;              ///< one multiplication
    static constexpr std::uint64_t kAdd = 1;               ///< one addition, subtraction or comparison
    static constexpr std::uint64_t kDiv = 5;               ///< one division
    static constexpr std::uint64_t kSqrt = 7;              ///< one square root
    static constexpr std::uint64_t kGpuMatrixProduct = 10; ///< one 4x4 product done by graphics hardware
};

/// Counts of elementary operations. Comparisons are counted as additions (a comparison is a subtraction).
struct OpTally {
    std::uint64_t mults = 0;              ///< multiplications
    std::uint64_t adds = 0;               ///< additions, subtractions, comparisons
    std::uint64_t divs = 0;               ///< divisions
    std::uint64_t sqrts = 0;              ///< square roots
    std::uint64_t gpuMatrixProducts = 0;  ///< 4x4 products left to graphics hardware

    /// Cost of these operations in FMULT.
    constexpr std::uint64_t fmult() const {
        return mults * FmultCost::kMult + adds * FmultCost::kAdd + divs * FmultCost::kDiv +
               sqrts * FmultCost::kSqrt + gpuMatrixProducts * FmultCost::kGpuMatrixProduct;
    }
    /// Adds another tally to this one.
    constexpr OpTally& operator+=(const OpTally& o) {
        mults += o.mults; adds += o.adds; divs += o.divs; sqrts += o.sqrts;
        gpuMatrixProducts += o.gpuMatrixProducts;
        return *this;
    }
    /// Exact equality, for tests.
    constexpr bool operator==(const OpTally&) const = default;
};

}  // namespace throng

// THRONG_TALLY(tallyPtr, mults, adds, divs, sqrts) records operations into an OpTally* when counting
// is compiled in (THRONG_OP_COUNTING=1) and the pointer is non-null. Compiled out, it vanishes, so
// hot paths pay nothing; compiled in with a null pointer, they pay one predictable branch.
//
// A tally states the operations of the code beside it, by these rules: every binary +, -, *, / on
// the kernel's numbers counts, multiplies by literals included (only arithmetic between constants is
// folded by the compiler); a comparison is an addition (std::min and std::max make one, std::clamp
// two, a sphere's emptiness test radius >= 0 one); sin, cos and acos are priced as square roots and
// fmod as a division; negation, abs and float/double conversions are free. The counted kernels are
// templates over their scalar (the detail/ headers), and tests/counting runs each on a number type
// that counts what it executes, checking every tally against it.
#ifndef THRONG_OP_COUNTING
#define THRONG_OP_COUNTING 1
#endif
#if THRONG_OP_COUNTING
#define THRONG_TALLY(tally, m, a, d, s)                                              \
    do {                                                                             \
        if (tally) {                                                                 \
            (tally)->mults += (m); (tally)->adds += (a);                             \
            (tally)->divs += (d); (tally)->sqrts += (s);                             \
        }                                                                            \
    } while (0)
#else
#define THRONG_TALLY(tally, m, a, d, s) do { (void)(tally); } while (0)
#endif
