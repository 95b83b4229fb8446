#include "core/color.h"

#include <algorithm>
#include <cmath>

namespace countershade {
namespace {

using color_constants::kWhite;

double lab_f(double t) { return color_constants::lab_f_lanes<double, int64_t>(t); }

}  // namespace

double srgb_decode(double code) {
  return code > 0.04045 ? std::pow((code + 0.055) / 1.055, 2.4) : code / 12.92;
}

double srgb_encode(double linear) {
  return linear > 0.0031308 ? 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055 : 12.92 * linear;
}

Lab xyz_to_lab(const glm::dvec3& xyz) {
  double fx = lab_f(xyz.x * color_constants::kInverseWhite[0]);
  double fy = lab_f(xyz.y * color_constants::kInverseWhite[1]);
  double fz = lab_f(xyz.z * color_constants::kInverseWhite[2]);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

double cielab_lightness(double Y) {
  return 116.0 * lab_f(Y * color_constants::kInverseWhite[1]) - 16.0;
}

Lab linear_rgb_to_lab(const glm::dvec3& rgb) { return xyz_to_lab(linear_rgb_to_xyz(rgb)); }

Lab srgb_to_lab(const glm::dvec3& srgb) {
  return linear_rgb_to_lab({srgb_decode(srgb.x), srgb_decode(srgb.y), srgb_decode(srgb.z)});
}

namespace {

constexpr double kPi = 3.14159265358979323846, kDegree = kPi / 180.0;

// The hue angle of (a', b') in radians, [0, 2π); 0 for a neutral colour.
double hue_angle(double a, double b) {
  if (a == 0.0 && b == 0.0) return 0.0;
  const double h = std::atan2(b, a);
  return h < 0.0 ? h + 2.0 * kPi : h;
}

// The mean hue of two colours, with Sharma et al.'s rule for the wrap-around (radians, in the
// order of operations of common implementations, so that exact half-turns round alike).
double mean_hue(double h1, double h2, double c_product) {
  double sum = h1 + h2;
  if (c_product == 0.0) return sum;
  if (std::abs(h1 - h2) > kPi) sum += sum < 2.0 * kPi ? 2.0 * kPi : -2.0 * kPi;
  return 0.5 * sum;
}

// The hue difference Δh' in radians, in [−π, π].
double hue_difference(double h1, double h2, double c_product) {
  if (c_product == 0.0) return 0.0;
  const double d = h2 - h1;
  if (d > kPi) return d - 2.0 * kPi;
  if (d < -kPi) return d + 2.0 * kPi;
  return d;
}

// x⁷ / (x⁷ + 25⁷) by multiplications (pow is the audit's hot spot).
double seventh_power_share(double x) {
  const double x2 = x * x, x7 = x2 * x2 * x2 * x;
  return x7 / (x7 + 6103515625.0);
}

// T of CIEDE2000 from one sine and cosine of the mean hue (multiple-angle identities).
double hue_weight(double h_mean) {
  const double c1 = std::cos(h_mean), s1 = std::sin(h_mean);
  const double c2 = 2.0 * c1 * c1 - 1.0, s2 = 2.0 * s1 * c1;
  const double c3 = c1 * (4.0 * c1 * c1 - 3.0), s3 = s1 * (3.0 - 4.0 * s1 * s1);
  const double c4 = 2.0 * c2 * c2 - 1.0, s4 = 2.0 * s2 * c2;
  auto shifted = [](double c, double s, double degrees) {  // cos(x + degrees)
    return c * std::cos(degrees * kDegree) - s * std::sin(degrees * kDegree);
  };
  return 1.0 - 0.17 * shifted(c1, s1, -30.0) + 0.24 * c2 + 0.32 * shifted(c3, s3, 6.0) -
         0.20 * shifted(c4, s4, -63.0);
}

}  // namespace

double ciede2000(const Lab& first, const Lab& second) {
  const double c_mean = 0.5 * (std::sqrt(first.a * first.a + first.b * first.b) +
                               std::sqrt(second.a * second.a + second.b * second.b));
  const double g = 0.5 * (1.0 - std::sqrt(seventh_power_share(c_mean)));
  const double a1 = (1.0 + g) * first.a, a2 = (1.0 + g) * second.a;
  const double c1 = std::sqrt(a1 * a1 + first.b * first.b),
               c2 = std::sqrt(a2 * a2 + second.b * second.b);
  const double h1 = hue_angle(a1, first.b), h2 = hue_angle(a2, second.b);
  const double dh = hue_difference(h1, h2, c1 * c2);
  const double dL = second.L - first.L, dC = c2 - c1;
  const double dH = 2.0 * std::sqrt(c1 * c2) * std::sin(0.5 * dh);
  const double L_mean = 0.5 * (first.L + second.L), c_mean_prime = 0.5 * (c1 + c2);
  const double h_mean = mean_hue(h1, h2, c1 * c2);
  const double l50 = (L_mean - 50.0) * (L_mean - 50.0);
  const double sL = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
  const double sC = 1.0 + 0.045 * c_mean_prime,
               sH = 1.0 + 0.015 * c_mean_prime * hue_weight(h_mean);
  const double rC = 2.0 * std::sqrt(seventh_power_share(c_mean_prime));
  const double z = (h_mean / kDegree - 275.0) / 25.0;
  const double d_theta = 30.0 * kDegree * std::exp(-z * z);
  const double rT = -std::sin(2.0 * d_theta) * rC;
  const double l = dL / sL, c = dC / sC, h = dH / sH;
  return std::sqrt(l * l + c * c + h * h + rT * c * h);
}

}  // namespace countershade
