#pragma once
// The three image filters of texture-space filtering (docs/methods.md, "Texture-space
// filtering"), each on one plane of CIELAB L* and each as a change of L* per unit strength λ, so
// that the filtered lightness at λ is L + λ·d for all three:
// - unsharp:   d = L − G_σ∗L                                  (gain λ on the detail)
// - bilateral: d = B(L) − L, B with spatial σ and range σ_r     (λ blends towards the abstraction)
// - dog:       d = −(1 − E)·L, E = 1 where D ≥ −τ, else 1 + tanh(φ·(D + τ)), D = G_σ∗L − G_1.6σ∗L
//              (dark edge lines multiplied into the lightness with strength λ)
// Textures wrap at their borders; rendered images are clamped.

#include <span>
#include <string>
#include <vector>

#include "core/parameters.h"

namespace countershade {

enum class FilterKind { unsharp, bilateral, dog };
inline constexpr double kMaxBilateralSigma = 8;
enum class Borders { wrap, clamp };

struct LightnessFilter {
  FilterKind kind = FilterKind::unsharp;
  double sigma = 2;     // spatial σ in samples (texels or pixels)
  double sigma_r = 10;  // bilateral: range σ in L*
  double tau = 1;       // dog: how far below 0 D must fall before a line starts, in L*
  double phi = 0.5;     // dog: steepness of the line's soft step, per L*
};

std::string filter_name(FilterKind kind);

// Reads `filter` (unsharp, bilateral, dog), `sigma` (default 2) and the chosen filter's own keys
// (`sigma_r`; `tau`, `phi`); a key of another filter is an InputError.
LightnessFilter read_lightness_filter(const ParameterBag& bag);

// d per sample for a width×height plane of L*, row-major.
std::vector<float> lightness_detail(std::span<const float> lightness, int width, int height,
                                    const LightnessFilter& filter, Borders borders,
                                    int threads = 0);

// A separable Gaussian in double precision over ±⌈4σ⌉ samples, normalised, with the given borders.
std::vector<double> gaussian_filter(std::span<const float> plane, int width, int height,
                                    double sigma, Borders borders, int threads = 0);

}  // namespace countershade
