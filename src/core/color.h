#pragma once
// CIELAB and sRGB conversions (D65 white, 2° observer, sRGB primaries), in double precision.
// The constants follow scikit-image, which produced the project's reference conversions.

#include <glm/vec3.hpp>

namespace countershade {

struct Lab {
  double L = 0, a = 0, b = 0;
};

// sRGB transfer function on one channel, [0,1] code <-> [0,1] linear.
double srgb_decode(double code);
double srgb_encode(double linear);

glm::dvec3 linear_rgb_to_xyz(const glm::dvec3& rgb);
glm::dvec3 xyz_to_linear_rgb(const glm::dvec3& xyz);
Lab xyz_to_lab(const glm::dvec3& xyz);
glm::dvec3 lab_to_xyz(const Lab& lab);

Lab linear_rgb_to_lab(const glm::dvec3& rgb);
glm::dvec3 lab_to_linear_rgb(const Lab& lab);
Lab srgb_to_lab(const glm::dvec3& srgb);

// Lightness-only change: L' = clamp(L_new, 0, 100) and a, b scaled by k = L'/L (k = 1 when
// L < 1e-6), so hue angle and saturation stay as they were.
Lab with_lightness(const Lab& lab, double new_lightness);

}  // namespace countershade
