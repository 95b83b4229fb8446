#include "enhance/light_alignment.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include "core/isa.h"
#include "core/lane_math.h"
#include "core/lane_vec3.h"

namespace countershade {
namespace {

constexpr double kDegenerate = 1e-12;

template <typename D>
[[gnu::always_inline]] inline D angle_between(const Vec3Lanes<D>& a, const Vec3Lanes<D>& b) {
  return acos_lanes(clamp_lanes(dot(a, b), -1.0, 1.0));
}

// Rodrigues' rotation of v about the unit axis k by θ in [0, π], normalised.
template <typename D>
[[gnu::always_inline]] inline Vec3Lanes<D> rotate(const Vec3Lanes<D>& v, const Vec3Lanes<D>& k,
                                                  const D& theta) {
  D s, c;
  sincos_lanes(theta, s, c);
  const Vec3Lanes<D> r = v * c + cross(k, v) * s + k * (dot(k, v) * (1.0 - c));
  return r * (1.0 / sqrt_lanes(dot(r, r)));
}

// One step of eq. 1 (light_alignment.h) for every lane; `strength` > 0. Each lane where the
// rotation is zero (no feature at this scale, the light along the coarser vector or on the guide)
// keeps `light` itself.
template <typename D>
[[gnu::always_inline]] inline Vec3Lanes<D> align_lanes(const Vec3Lanes<D>& light,
                                                       const Vec3Lanes<D>& fine,
                                                       const Vec3Lanes<D>& z, double strength,
                                                       double damping) {
  // Frame: z the coarser vector, x the finer one's part across it (its length is λ2).
  const Vec3Lanes<D> across = fine - z * dot(fine, z);
  const D lambda2 = sqrt_lanes(dot(across, across));
  const Vec3Lanes<D> x = across / lambda2;
  // The guide: the finer vector when the light lies on its side of the frame, else the tangent
  // to it in the (x, z) plane on the light's side (so that the light is turned to graze it).
  const auto bright = dot(light, x) >= 0.0;
  const Vec3Lanes<D> guide = select_lanes(bright, fine, z * dot(fine, x) - x * dot(fine, z));
  const D angle = angle_between(light, guide);
  // λ1 measures how far the light is from the switching point dot(l, x) = 0, by the angle between
  // the light and the guide projected across z (the guide's projection is ±x): 1 when the light
  // lies along it, 0 at the switch, so the rotation fades out on both sides and the shading has
  // no jump there. (The 3D angle would leave a jump of up to 0.7 in n·l.)
  const Vec3Lanes<D> light_across = light - z * dot(light, z);
  const D across_length = sqrt_lanes(dot(light_across, light_across));
  const D side = bright ? 1.0 : -1.0;
  const D lambda1 =
      1.0 - 2.0 * angle_between(light_across / across_length, x * side) / std::numbers::pi;
  // W_γ(λ1·λ2), with e^{−γ} = damping.
  const D w = clamp_lanes(lambda1 * lambda2, 0.0, 1.0);
  const D theta = std::min(strength, 1.0) * (w / (damping * (1.0 - w) + w)) * angle;
  const Vec3Lanes<D> axis = cross(light, guide);
  const D axis_length = sqrt_lanes(dot(axis, axis));
  const auto turns = (lambda2 >= kDegenerate) & (across_length >= kDegenerate) & (theta > 0.0) &
                     (axis_length >= kDegenerate);
  return select_lanes(turns, rotate(light, axis / axis_length, theta), light);
}

// The cascade of align_light for every lane; vectors[k] holds v_{k+1}.
template <typename D>
[[gnu::always_inline]] inline Vec3Lanes<D> cascade_lanes(Vec3Lanes<D> l,
                                                         const Vec3Lanes<D>* vectors, size_t count,
                                                         std::span<const double> strengths,
                                                         double damping) {
  for (size_t i = count - 1; i-- > 0;)
    if (i < strengths.size() && strengths[i] > 0)
      l = align_lanes(l, vectors[i], vectors[i + 1], strengths[i], damping);
  return l;
}

Vec3Lanes<double> lanes_of(const glm::dvec3& v) { return {v.x, v.y, v.z}; }
glm::dvec3 vector_of(const Vec3Lanes<double>& v) { return {v.x, v.y, v.z}; }

// align_light_block on the lanes of D at once.
template <typename D>
[[gnu::always_inline]] inline void align_light_lanes(AlignmentBlock& block, size_t count,
                                                     size_t scales,
                                                     std::span<const double> strengths,
                                                     double damping) {
  constexpr size_t kLanes = sizeof(D) / sizeof(double);
  static_assert(kAlignmentBlock % kLanes == 0);
  scales = std::min(scales, kMaxAlignmentScales);
  for (size_t first = 0; first < count; first += kLanes) {
    if (scales < 2) {
      for (int c = 0; c < 3; ++c)
        std::copy_n(block.light[c] + first, kLanes, block.aligned[c] + first);
      continue;
    }
    Vec3Lanes<D> v[kMaxAlignmentScales];
    for (size_t k = 0; k < scales; ++k) v[k] = load_lanes<D>(block.vectors[k], first);
    const auto l = cascade_lanes(load_lanes<D>(block.light, first), v, scales, strengths, damping);
    store_lanes(l, block.aligned, first);
  }
}

COUNTERSHADE_AVX512_FUNCTION
void align_light_avx512(AlignmentBlock& block, size_t count, size_t scales,
                        std::span<const double> strengths, double damping) {
  align_light_lanes<WideLanes>(block, count, scales, strengths, damping);
}

COUNTERSHADE_AVX2_CLONES
void align_light_avx2(AlignmentBlock& block, size_t count, size_t scales,
                      std::span<const double> strengths, double damping) {
  align_light_lanes<NarrowLanes>(block, count, scales, strengths, damping);
}

}  // namespace

AlignmentWeight::AlignmentWeight(double gamma) : damping_(std::exp(-gamma)) {}

double AlignmentWeight::operator()(double x) const {
  x = std::clamp(x, 0.0, 1.0);
  return x / (damping_ * (1 - x) + x);
}

double alignment_weight(double x, double gamma) { return AlignmentWeight(gamma)(x); }

glm::dvec3 align_one_scale(const glm::dvec3& light, const glm::dvec3& fine,
                           const glm::dvec3& coarse, double strength,
                           const AlignmentWeight& weight) {
  if (!(strength > 0)) return light;
  return vector_of(
      align_lanes(lanes_of(light), lanes_of(fine), lanes_of(coarse), strength, weight.damping()));
}

glm::dvec3 align_light(const glm::dvec3& light, std::span<const glm::dvec3> vectors,
                       std::span<const double> strengths, const AlignmentWeight& weight) {
  Vec3Lanes<double> v[kMaxAlignmentScales];
  const size_t count = std::min(vectors.size(), kMaxAlignmentScales);
  for (size_t k = 0; k < count; ++k) v[k] = lanes_of(vectors[k]);
  if (count < 2) return light;
  return vector_of(cascade_lanes(lanes_of(light), v, count, strengths, weight.damping()));
}

void align_light_block(AlignmentBlock& block, size_t count, size_t scales,
                       std::span<const double> strengths, double damping) {
  (has_avx512() ? align_light_avx512 : align_light_avx2)(block, count, scales, strengths, damping);
}

}  // namespace countershade
