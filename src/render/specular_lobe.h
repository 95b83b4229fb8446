#pragma once
// Directions drawn from a material's specular lobe, for an environment sampled by both the cosine
// and the lobe ("sampling": "cosine+specular"). A glossy surface mirrors a bright sky in a narrow
// cone of directions that cosine sampling seldom draws, so its pixels need hundreds of samples to
// meet the noise budget; drawing some of the environment's directions from the lobe, and dividing
// every sample by the mixture's density (the balance heuristic), removes most of that variance
// without changing the expected image.

#include <glm/vec3.hpp>
#include <optional>

#include "render/directions.h"
#include "render/scene.h"

namespace countershade {

// GGX's α² for a material as the shader takes it (α = roughness²), and its distribution of half
// vectors D at cos θh = `cos_h`: shared by the BRDF and the lobe's sampling density.
double ggx_alpha2(const Material& m);
double ggx_distribution(double alpha2, double cos_h);

// Whether a material has a lobe to sample (a specular model).
bool has_specular_lobe(const Material& m);

// A direction towards the light: a half vector drawn with density D(h)·cos θh (GGX) or
// (s + 1)/2π · cos^s θh (Blinn–Phong) around the normal (the frame's axis), and `wo` reflected
// about it. None where the half vector faces away from `wo`.
std::optional<glm::dvec3> sample_specular_lobe(const Material& m, const TangentFrame& n,
                                               const glm::dvec3& wo, double u1, double u2);

// The solid-angle density with which sample_specular_lobe draws `wi`: pdf(h) / (4 |wo·h|).
double specular_lobe_pdf(const Material& m, const glm::dvec3& n, const glm::dvec3& wo,
                         const glm::dvec3& wi);

}  // namespace countershade
