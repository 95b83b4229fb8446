#pragma once
// CIELAB and sRGB conversions (D65 white, 2° observer, sRGB primaries), in double precision.
// The constants follow scikit-image, which produced the project's reference conversions.

#include <algorithm>
#include <bit>
#include <cstdint>
#include <glm/vec3.hpp>

namespace countershade {

struct Lab {
  double L = 0, a = 0, b = 0;
};

// sRGB transfer function on one channel, [0,1] code <-> [0,1] linear.
double srgb_decode(double code);
double srgb_encode(double linear);

namespace color_constants {

// D65 reference white (2° observer) and the sRGB -> XYZ matrix as used by scikit-image.
inline constexpr double kWhite[3] = {0.95047, 1.0, 1.08883};
inline constexpr double kInverseWhite[3] = {1.0 / 0.95047, 1.0, 1.0 / 1.08883};
inline constexpr double kRgbToXyz[3][3] = {
    {0.412453, 0.357580, 0.180423}, {0.212671, 0.715160, 0.072169}, {0.019334, 0.119193, 0.950227}};

struct Matrix3 {
  double m[3][3];
};
// The inverse by cofactors, evaluated at compile time (each operation correctly rounded, as at
// run time).
constexpr Matrix3 inverse(const double (&a)[3][3]) {
  const double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                     a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                     a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  Matrix3 r{};
  r.m[0][0] = (a[1][1] * a[2][2] - a[1][2] * a[2][1]) / det;
  r.m[0][1] = (a[0][2] * a[2][1] - a[0][1] * a[2][2]) / det;
  r.m[0][2] = (a[0][1] * a[1][2] - a[0][2] * a[1][1]) / det;
  r.m[1][0] = (a[1][2] * a[2][0] - a[1][0] * a[2][2]) / det;
  r.m[1][1] = (a[0][0] * a[2][2] - a[0][2] * a[2][0]) / det;
  r.m[1][2] = (a[0][2] * a[1][0] - a[0][0] * a[1][2]) / det;
  r.m[2][0] = (a[1][0] * a[2][1] - a[1][1] * a[2][0]) / det;
  r.m[2][1] = (a[0][1] * a[2][0] - a[0][0] * a[2][1]) / det;
  r.m[2][2] = (a[0][0] * a[1][1] - a[0][1] * a[1][0]) / det;
  return r;
}
inline constexpr Matrix3 kXyzToRgb = inverse(kRgbToXyz);

inline glm::dvec3 apply(const double (&m)[3][3], const glm::dvec3& v) {
  return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
          m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
          m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

// Divisions by constants are multiplications by their reciprocals: the lightness composition runs
// these for millions of pixels, and a division costs several multiplications.
inline constexpr double k1_116 = 1.0 / 116.0, k1_500 = 1.0 / 500.0, k1_200 = 1.0 / 200.0,
                        k1_7787 = 1.0 / 7.787;

inline double lab_f_inverse(double t) {
  return t > 0.2068966 ? t * t * t : (t - 16.0 / 116.0) * k1_7787;
}

// The cube root for t in [2^-300, 2^300], within a few ulp, from +, −, ×, ÷ and the exponent bits
// only: t = m·2^e with m in [1,2); e = 3q + r; cbrt(t) = cbrt(m·2^r)·2^q. Written once for scalars
// (D = double, I = int64_t) and for GCC vectors of doubles with their int64 lanes, so that the
// vectorised conversion (display_to_lab) computes exactly the scalar values.
template <typename D, typename I>
[[gnu::always_inline]] inline D cube_root_lanes(D t) {
  const I bits = __builtin_bit_cast(I, t);
  I e = (bits >> 52) - 1023;
  e = e < -300 ? -300 : (e > 300 ? 300 : e);
  const D m = __builtin_bit_cast(D, (bits & 0x000FFFFFFFFFFFFFll) | 0x3FF0000000000000ll);
  const I q = (((e + 300) * 21846) >> 16) - 100;  // floor(e / 3) for |e| ≤ 300
  const I r = e - 3 * q;
  // cbrt on [1, 2) to 2e-7 (a least-squares polynomial), times cbrt(2^r); one Halley step then
  // brings it to within a few ulp.
  D y = 0.4476214805743782 +
        m * (0.9480536967987485 +
             m * (-0.6625905808117523 +
                  m * (0.3820491194094191 +
                       m * (-0.14276857566904744 +
                            m * (0.03044327453163275 + m * -0.0028082221513328876)))));
  const D x = m * (r == 0 ? 1.0 : (r == 1 ? 2.0 : 4.0));
  y *= r == 0 ? 1.0 : (r == 1 ? 1.2599210498948732 : 1.5874010519681994);
  const D y3 = y * y * y;
  y = y * (y3 + 2.0 * x) / (2.0 * y3 + x);
  return y * __builtin_bit_cast(D, (q + 1023) << 52);
}
inline double cube_root(double t) { return cube_root_lanes<double, int64_t>(t); }

// CIELAB's f(t): the cube root above 0.008856, the linear segment below; for scalars and lanes
// alike.
template <typename D, typename I>
[[gnu::always_inline]] inline D lab_f_lanes(D t) {
  return t > 0.008856 ? cube_root_lanes<D, I>(t) : 7.787 * t + 16.0 / 116.0;
}

}  // namespace color_constants

// The conversions towards linear RGB are inline: the lightness composition runs them for
// millions of pixels per stimulus.
inline glm::dvec3 linear_rgb_to_xyz(const glm::dvec3& rgb) {
  return color_constants::apply(color_constants::kRgbToXyz, rgb);
}
inline glm::dvec3 xyz_to_linear_rgb(const glm::dvec3& xyz) {
  return color_constants::apply(color_constants::kXyzToRgb.m, xyz);
}
Lab xyz_to_lab(const glm::dvec3& xyz);
inline glm::dvec3 lab_to_xyz(const Lab& lab) {
  using namespace color_constants;
  const double fy = (lab.L + 16.0) * k1_116;
  const double fx = lab.a * k1_500 + fy;
  const double fz = fy - lab.b * k1_200;
  return {lab_f_inverse(fx) * kWhite[0], lab_f_inverse(fy) * kWhite[1],
          lab_f_inverse(fz) * kWhite[2]};
}

Lab linear_rgb_to_lab(const glm::dvec3& rgb);
inline glm::dvec3 lab_to_linear_rgb(const Lab& lab) { return xyz_to_linear_rgb(lab_to_xyz(lab)); }
Lab srgb_to_lab(const glm::dvec3& srgb);

// CIELAB L* of a relative luminance Y (white = 1), as linear_rgb_to_lab computes it.
double cielab_lightness(double Y);
// The relative luminance Y whose CIELAB L* is `lightness` (the inverse of cielab_lightness).
inline double luminance_of_lightness(double lightness) {
  return color_constants::lab_f_inverse((lightness + 16.0) * color_constants::k1_116) *
         color_constants::kWhite[1];
}
// The luminance Y of linear sRGB (the second row of the sRGB -> XYZ matrix).
inline double luminance_of(const glm::dvec3& rgb) {
  const auto& m = color_constants::kRgbToXyz;
  return m[1][0] * rgb.x + m[1][1] * rgb.y + m[1][2] * rgb.z;
}

// The CIEDE2000 colour difference (k_L = k_C = k_H = 1), as specified by Sharma, Wu and Dalal
// (2005), hue-angle wrap-arounds and neutral colours included.
double ciede2000(const Lab& first, const Lab& second);

// Lightness-only change: L' = clamp(L_new, 0, 100) and a, b scaled by k = L'/L (k = 1 when
// L < 1e-6), so hue angle and saturation stay as they were.
inline Lab with_lightness(const Lab& lab, double new_lightness) {
  const double L = new_lightness < 0.0 ? 0.0 : (new_lightness > 100.0 ? 100.0 : new_lightness);
  const double k = lab.L < 1e-6 ? 1.0 : L / lab.L;
  return {L, k * lab.a, k * lab.b};
}

}  // namespace countershade
