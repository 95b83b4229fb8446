#include "core/color.h"

#include <algorithm>
#include <cmath>

namespace countershade {
namespace {

// D65 reference white (2° observer) and the sRGB -> XYZ matrix as used by scikit-image.
constexpr double kWhite[3] = {0.95047, 1.0, 1.08883};
constexpr double kRgbToXyz[3][3] = {{0.412453, 0.357580, 0.180423},
                                    {0.212671, 0.715160, 0.072169},
                                    {0.019334, 0.119193, 0.950227}};

struct Inverse3 {
  double m[3][3];
  Inverse3() {
    const auto& a = kRgbToXyz;
    double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
                 a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                 a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
    m[0][0] = (a[1][1] * a[2][2] - a[1][2] * a[2][1]) / det;
    m[0][1] = (a[0][2] * a[2][1] - a[0][1] * a[2][2]) / det;
    m[0][2] = (a[0][1] * a[1][2] - a[0][2] * a[1][1]) / det;
    m[1][0] = (a[1][2] * a[2][0] - a[1][0] * a[2][2]) / det;
    m[1][1] = (a[0][0] * a[2][2] - a[0][2] * a[2][0]) / det;
    m[1][2] = (a[0][2] * a[1][0] - a[0][0] * a[1][2]) / det;
    m[2][0] = (a[1][0] * a[2][1] - a[1][1] * a[2][0]) / det;
    m[2][1] = (a[0][1] * a[2][0] - a[0][0] * a[2][1]) / det;
    m[2][2] = (a[0][0] * a[1][1] - a[0][1] * a[1][0]) / det;
  }
};
const Inverse3 kXyzToRgb;

glm::dvec3 apply(const double (&m)[3][3], const glm::dvec3& v) {
  return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
          m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
          m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

double lab_f(double t) { return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116.0; }
double lab_f_inverse(double t) {
  return t > 0.2068966 ? t * t * t : (t - 16.0 / 116.0) / 7.787;
}

}  // namespace

double srgb_decode(double code) {
  return code > 0.04045 ? std::pow((code + 0.055) / 1.055, 2.4) : code / 12.92;
}

double srgb_encode(double linear) {
  return linear > 0.0031308 ? 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055 : 12.92 * linear;
}

glm::dvec3 linear_rgb_to_xyz(const glm::dvec3& rgb) { return apply(kRgbToXyz, rgb); }
glm::dvec3 xyz_to_linear_rgb(const glm::dvec3& xyz) { return apply(kXyzToRgb.m, xyz); }

Lab xyz_to_lab(const glm::dvec3& xyz) {
  double fx = lab_f(xyz.x / kWhite[0]);
  double fy = lab_f(xyz.y / kWhite[1]);
  double fz = lab_f(xyz.z / kWhite[2]);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

glm::dvec3 lab_to_xyz(const Lab& lab) {
  double fy = (lab.L + 16.0) / 116.0;
  double fx = lab.a / 500.0 + fy;
  double fz = fy - lab.b / 200.0;
  return {lab_f_inverse(fx) * kWhite[0], lab_f_inverse(fy) * kWhite[1],
          lab_f_inverse(fz) * kWhite[2]};
}

Lab linear_rgb_to_lab(const glm::dvec3& rgb) { return xyz_to_lab(linear_rgb_to_xyz(rgb)); }
glm::dvec3 lab_to_linear_rgb(const Lab& lab) { return xyz_to_linear_rgb(lab_to_xyz(lab)); }

Lab srgb_to_lab(const glm::dvec3& srgb) {
  return linear_rgb_to_lab({srgb_decode(srgb.x), srgb_decode(srgb.y), srgb_decode(srgb.z)});
}

Lab with_lightness(const Lab& lab, double new_lightness) {
  double L = std::clamp(new_lightness, 0.0, 100.0);
  double k = lab.L < 1e-6 ? 1.0 : L / lab.L;
  return {L, k * lab.a, k * lab.b};
}

}  // namespace countershade
