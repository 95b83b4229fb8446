#pragma once
// Local light alignment (Mestres et al. 2021, §4–5; docs/methods.md): the light direction is
// rotated per shading point, from the coarsest scale to the finest, towards a guide built from two
// successive scales of the normal field, so that each feature gets one fully lit and one unlit
// side.

#include <cstddef>
#include <glm/vec3.hpp>
#include <span>

namespace countershade {

// W_γ(x) = x / (e^{−γ}(1 − x) + x) on x clamped to [0, 1]: W(0) = 0, W(1) = 1, monotone; γ = 0 is
// the identity. It keeps the rotation small near the places where the guide switches sides.
double alignment_weight(double x, double gamma);

// W_γ with e^{−γ} computed once: it is evaluated for every scale of every light sample. Made
// implicitly from γ.
class AlignmentWeight {
 public:
  AlignmentWeight(double gamma);  // NOLINT(google-explicit-constructor)
  double operator()(double x) const;
  double damping() const { return damping_; }

 private:
  double damping_;  // e^{−γ}
};

// One step of eq. 1: `light` (unit, towards the light) rotated towards the guide of the finer
// vector `fine` (n_i, or a reflected view vector r_i) in the frame of the coarser `coarse`
// (n_{i+1}), by the fraction strength·W_γ(λ1·λ2) of the angle between them. Returns `light`
// itself when the rotation is zero (strength 0, no feature, or the light on the guide).
glm::dvec3 align_one_scale(const glm::dvec3& light, const glm::dvec3& fine,
                           const glm::dvec3& coarse, double strength,
                           const AlignmentWeight& weight);

// The whole cascade: l_S = light, then l_i = align_one_scale(l_{i+1}, v_i, v_{i+1}, s_i) for
// i = S−1 … 1. `vectors` holds v_1 (finest) … v_S (coarsest), all unit; `strengths` s_1 … s_{S−1}.
glm::dvec3 align_light(const glm::dvec3& light, std::span<const glm::dvec3> vectors,
                       std::span<const double> strengths, const AlignmentWeight& weight);

// The cascade for many shading points at once, vectorised, each with the same result as align_light
// bit for bit (both evaluate one lane-generic code; core/lane_math.h). Planes hold one coordinate
// of one vector per point: `light` the direction to the light, vectors[k] v_{k+1} (finest first).
inline constexpr size_t kMaxAlignmentScales = 8;
inline constexpr size_t kAlignmentBlock = 64;
struct AlignmentBlock {
  double light[3][kAlignmentBlock] = {};
  double vectors[kMaxAlignmentScales][3][kAlignmentBlock] = {};
  double aligned[3][kAlignmentBlock] = {};  // the result
};
// Aligns points 0 … count−1 (count ≤ kAlignmentBlock) over `scales` vectors with strengths s_1 …
// s_{S−1} and W_γ's e^{−γ} = `damping` (AlignmentWeight::damping). Points past `count` are
// computed from whatever their planes hold and may be ignored.
void align_light_block(AlignmentBlock& block, size_t count, size_t scales,
                       std::span<const double> strengths, double damping);

}  // namespace countershade
