#pragma once
// Sines and cosines of many angles, two at a time through glibc's vector math library (libmvec)
// where it is present, else through std::sin and std::cos. An angle gets the same bits whichever
// call computes it and whatever its neighbours are (a lone angle takes a lane of its own), so
// batched and single callers agree and results do not depend on how work is split over threads.

#include <cstddef>

namespace throng::detail {

/// Whether the vector library serves sinCos (false: std::sin and std::cos, one angle at a time).
bool sinCosVectorised();

/// sines[k] = sin(angles[k]) and cosines[k] = cos(angles[k]) for k < n (libmvec: at most 4 ulp
/// from the exact values, like std::sin; not always the same bits as std::sin).
void sinCos(const double* angles, double* sines, double* cosines, std::size_t n);

/// The sine and cosine of one angle, the same bits as sinCos over any batch holding it.
inline void sinCos(double angle, double& sine, double& cosine) { sinCos(&angle, &sine, &cosine, 1); }

}  // namespace throng::detail
