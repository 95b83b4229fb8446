#pragma once
// Light warping's direction warp (the method lives in light_warping.cpp), for the method and tests.

#include <glm/vec3.hpp>
#include <span>

namespace countershade {

// The unit light direction `wi` rotated in its plane with the view-reflected direction `r`: the
// angle φ between them becomes f·φ with f = e/(1 + (e − 1)·φ/π), e = exp(−amount·κ), the amount of
// warping being λ·α. Convex parts (κ > 0) pull the light towards r, concave parts push it away,
// and φ stays within [0, π].
glm::dvec3 warp_light(const glm::dvec3& wi, const glm::dvec3& r, double kappa, double amount);

// warp_light of every sample k (wi[k], r[k], kappa[k]) into out[k], many at once in vector lanes:
// the same bits as one at a time (both are one code, core/lane_math.h).
void warp_lights(std::span<const glm::dvec3> wi, std::span<const glm::dvec3> r,
                 std::span<const double> kappa, double amount, glm::dvec3* out);

}  // namespace countershade
