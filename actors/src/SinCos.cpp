// Two angles per call of libmvec's SSE2 sine and cosine (glibc's vector ABI, `b` = 128-bit
// registers, `N2` = unmasked, two lanes): about three times the throughput of the scalar sincos, and
// on every x86-64 machine. Phase 1 of both processing methods computes one sine and cosine per
// walking actor per frame through it (RefpointKernel.h).

#include "throng/actors/detail/SinCos.h"

#include <cmath>

#if THRONG_HAVE_LIBMVEC
#include <emmintrin.h>

extern "C" {
__m128d _ZGVbN2v_sin(__m128d);  // glibc 2.22+, libmvec
__m128d _ZGVbN2v_cos(__m128d);
}
#endif

namespace throng::detail {

bool sinCosVectorised() { return THRONG_HAVE_LIBMVEC != 0; }

void sinCos(const double* angles, double* sines, double* cosines, std::size_t n) {
#if THRONG_HAVE_LIBMVEC
    std::size_t k = 0;
    for (; k + 2 <= n; k += 2) {
        const __m128d a = _mm_loadu_pd(angles + k);
        _mm_storeu_pd(sines + k, _ZGVbN2v_sin(a));
        _mm_storeu_pd(cosines + k, _ZGVbN2v_cos(a));
    }
    if (k < n) {  // the last angle alone, in both lanes: the bits it would get beside any other
        const __m128d a = _mm_set1_pd(angles[k]);
        sines[k] = _mm_cvtsd_f64(_ZGVbN2v_sin(a));
        cosines[k] = _mm_cvtsd_f64(_ZGVbN2v_cos(a));
    }
#else
    for (std::size_t k = 0; k < n; ++k) {
        sines[k] = std::sin(angles[k]);
        cosines[k] = std::cos(angles[k]);
    }
#endif
}

}  // namespace throng::detail
