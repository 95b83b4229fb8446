#pragma once
// Separable Gaussian blur of one-channel float images with clamp-to-edge borders.
//
// gaussian_blur: a 4th-order recursive (Deriche) filter, run as two parallel second-order sections
// (in float, in double for σ > 48), whose cost does not depend on σ; a step's error is ≤ 8.2e-5.
// It filters several lines at once so it vectorises, and is multithreaded. Small σ (below
// kRecursiveMinSigma) uses the exact FIR path, whose cost is then bounded by a ~25-tap kernel.
// gaussian_blur_exact: the reference: a double-precision FIR over ±4σ, normalised.

#include <vector>

namespace countershade {

inline constexpr double kRecursiveMinSigma = 3.0;

// `in` and `out` are width×height, row-major; they may be the same buffer. σ in pixels (> 0).
void gaussian_blur(const float* in, float* out, int width, int height, double sigma,
                   int threads = 0);
void gaussian_blur_exact(const float* in, float* out, int width, int height, double sigma,
                         int threads = 0);

}  // namespace countershade
