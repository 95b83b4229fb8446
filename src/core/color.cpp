#include "core/color.h"

#include <algorithm>
#include <cmath>

namespace countershade {
namespace {

using color_constants::kWhite;

double lab_f(double t) { return t > 0.008856 ? color_constants::cube_root(t) : 7.787 * t + 16.0 / 116.0; }

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

double cielab_lightness(double Y) { return 116.0 * lab_f(Y * color_constants::kInverseWhite[1]) - 16.0; }

Lab linear_rgb_to_lab(const glm::dvec3& rgb) { return xyz_to_lab(linear_rgb_to_xyz(rgb)); }

Lab srgb_to_lab(const glm::dvec3& srgb) {
  return linear_rgb_to_lab({srgb_decode(srgb.x), srgb_decode(srgb.y), srgb_decode(srgb.z)});
}

}  // namespace countershade
