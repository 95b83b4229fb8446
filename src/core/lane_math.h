#pragma once
// Elementary functions written once for scalars (D = double) and for GCC vectors of doubles, so
// that a loop vectorised over many points computes exactly what the scalar code computes for one
// (as cube_root_lanes in core/color.h). Only +, −, ×, ÷, comparisons and the square root, which
// IEEE rounds correctly in both forms; the build keeps a*b+c unfused (CMakeLists.txt).
//
// Conditions are lane masks: `m ? a : b` selects per lane for vectors and is the usual choice for
// scalars, and every branch is computed, so a lane that takes no part in a result may hold any
// value (even NaN) without a trap or undefined behaviour.

#include <cmath>
#include <type_traits>

namespace countershade {

// A number, or each lane of a vector, converted to To (floating point to integer truncates).
template <typename To, typename From>
[[gnu::always_inline]] inline To convert_lanes(From x) {
  if constexpr (std::is_scalar_v<From>) {
    return To(x);
  } else {
    return __builtin_convertvector(x, To);
  }
}

template <typename D>
[[gnu::always_inline]] inline D sqrt_lanes(D x) {
  if constexpr (std::is_same_v<D, double>) {
    return std::sqrt(x);
  } else {
    D out = x;
    for (int lane = 0; lane < int(sizeof(D) / sizeof(double)); ++lane)
      out[lane] = __builtin_sqrt(x[lane]);
    return out;
  }
}

template <typename D>
[[gnu::always_inline]] inline D clamp_lanes(D x, double lo, double hi) {
  return x < lo ? lo : (x > hi ? hi : x);
}

// Polynomial c[0]·u^(n−1) + … + c[n−1] by Horner's rule.
template <typename D, int N>
[[gnu::always_inline]] inline D horner_lanes(D u, const double (&c)[N]) {
  D sum = u * c[0] + c[1];
  for (int k = 2; k < N; ++k) sum = sum * u + c[k];
  return sum;
}

// acos(x) for x in [−1, 1], within 5e-16 (2 ulp of π). asin(y) = y + y³·R(y²) on y in [0, ½] (R a
// degree-11 Chebyshev fit, 6e-17 relative); |x| ≤ ½ gives π/2 − asin|x|, |x| > ½ gives
// 2·asin(√((1 − |x|)/2)), and a negative x gives π minus the value of |x|.
template <typename D>
[[gnu::always_inline]] inline D acos_lanes(D x) {
  constexpr double kR[] = {0.028169218060881413,  -0.010749050339697808, 0.016035514349148823,
                           0.0078029494773533171, 0.011875494382636923,  0.013929652902326633,
                           0.017355259955786322,  0.02237204763174451,   0.030381947367098481,
                           0.044642857103423643,  0.075000000000207644,  0.16666666666666649};
  constexpr double kHalfPi = 1.5707963267948966, kPi = 3.141592653589793;
  const D a = x < 0.0 ? -x : x;
  const auto small = a <= 0.5;
  const D u = small ? a * a : (1.0 - a) * 0.5;
  const D y = small ? a : sqrt_lanes(u);
  const D asin_y = y + y * u * horner_lanes(u, kR);
  const D acos_a = small ? kHalfPi - asin_y : 2.0 * asin_y;
  return x < 0.0 ? kPi - acos_a : acos_a;
}

// sin θ and cos θ for θ in [0, π], within 2e-16: θ = k·π/2 + r with k in {0, 1, 2} and |r| ≤ π/4,
// then Taylor polynomials in r (the first omitted terms are below 5e-17 there).
template <typename D>
[[gnu::always_inline]] inline void sincos_lanes(D theta, D& sin_out, D& cos_out) {
  constexpr double kSin[] = {
      -1.0 / 1307674368000.0, 1.0 / 6227020800.0, -1.0 / 39916800.0, 1.0 / 362880.0,
      -1.0 / 5040.0,          1.0 / 120.0,        -1.0 / 6.0};
  constexpr double kCos[] = {
      1.0 / 20922789888000.0, -1.0 / 87178291200.0, 1.0 / 479001600.0, -1.0 / 3628800.0,
      1.0 / 40320.0,          -1.0 / 720.0,         1.0 / 24.0};
  constexpr double kTwoOverPi = 0.6366197723675814, kRound = 6755399441055744.0;  // 1.5·2^52
  constexpr double kHalfPiHigh = 1.5707963267948966, kHalfPiLow = 6.123233995736766e-17;
  const D k = (theta * kTwoOverPi + kRound) - kRound;      // nearest integer (the sum rounds it)
  const D r = (theta - k * kHalfPiHigh) - k * kHalfPiLow;  // k·high is exact for k ≤ 2
  const D r2 = r * r;
  const D s = r + r * r2 * horner_lanes(r2, kSin);
  const D c = (1.0 - 0.5 * r2) + r2 * r2 * horner_lanes(r2, kCos);
  sin_out = k == 0.0 ? s : (k == 1.0 ? c : -s);
  cos_out = k == 0.0 ? c : (k == 1.0 ? -s : -c);
}

// e^x within 2 ulp for x in [−700, 700]; x is clamped there (NaN gives e^−700). x = n·ln 2 + r
// with |r| ≤ ln 2 / 2, e^r by its Taylor polynomial to r^13 (the next term is below 5e-18), times
// 2^n made from the exponent bits. I: int64_t, or the GCC vector of int64 lanes matching D.
template <typename D, typename I>
[[gnu::always_inline]] inline D exp_lanes(D x) {
  constexpr double kTaylor[] = {1.0 / 6227020800.0,
                                1.0 / 479001600.0,
                                1.0 / 39916800.0,
                                1.0 / 3628800.0,
                                1.0 / 362880.0,
                                1.0 / 40320.0,
                                1.0 / 5040.0,
                                1.0 / 720.0,
                                1.0 / 120.0,
                                1.0 / 24.0,
                                1.0 / 6.0,
                                0.5,
                                1.0,
                                1.0};
  constexpr double kLog2e = 1.4426950408889634, kRound = 6755399441055744.0;
  // ln 2 in two parts; the first has 32 significant bits, so n·high is exact for |n| < 2^21.
  constexpr double kLn2High = 6.93147180369123816490e-01, kLn2Low = 1.90821492927058770002e-10;
  x = x > -700.0 ? (x < 700.0 ? x : 700.0) : -700.0;
  const D n = (x * kLog2e + kRound) - kRound;
  const D r = (x - n * kLn2High) - n * kLn2Low;
  const I k = convert_lanes<I>(n);
  return horner_lanes(r, kTaylor) * __builtin_bit_cast(D, (k + 1023) << 52);
}

}  // namespace countershade
