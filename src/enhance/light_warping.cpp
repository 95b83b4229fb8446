// Light warping (Vergne et al. 2009), as methods.md reads it: every light sample's direction is
// turned towards the view-reflected direction on convex parts and away from it on concave parts,
// by the view curvature κ of radiance scaling, with the amount of warping α (16.62 by default,
// Mestres et al. 2021's Fig. 14) scaled by λ. λ = 0 is the plain render; shadows are the plain
// ones (the shading hook).

#include "enhance/light_warping.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <glm/geometric.hpp>
#include <numbers>
#include <span>
#include <vector>

#include "core/isa.h"
#include "core/lane_math.h"
#include "core/lane_vec3.h"
#include "enhance/method.h"
#include "enhance/shading_method.h"
#include "enhance/view_curvature.h"
#include "render/shading.h"

namespace countershade {

namespace {

// The warp of light_warping.h for every lane (core/lane_math.h), so that the hook's blocks and
// one sample at a time give the same bits.
template <typename D, typename I>
[[gnu::always_inline]] inline Vec3Lanes<D> warp_lanes(const Vec3Lanes<D>& wi, const Vec3Lanes<D>& r,
                                                      const D& kappa, double amount) {
  const D cos_angle = clamp_lanes(dot(wi, r), -1.0, 1.0);
  const Vec3Lanes<D> across = wi - r * cos_angle;  // wi's part perpendicular to r
  const D across_length = sqrt_lanes(dot(across, across));
  const D angle = acos_lanes(cos_angle);
  const D e = exp_lanes<D, I>(-amount * kappa);
  const D warped = angle * e / (1.0 + (e - 1.0) * angle / std::numbers::pi);  // in [0, π]
  D sin_warped, cos_warped;
  sincos_lanes(warped, sin_warped, cos_warped);
  // Along r or opposite it the warp keeps the light.
  return select_lanes(across_length < 1e-12, wi,
                      r * cos_warped + (across / across_length) * sin_warped);
}

constexpr size_t kWarpBlock = 64;

// Planes of one coordinate per light sample.
struct WarpBlock {
  double wi[3][kWarpBlock] = {}, r[3][kWarpBlock] = {}, kappa[kWarpBlock] = {};
  double warped[3][kWarpBlock] = {};
};

// Warps samples 0 … count−1 of the block on the lanes of D at once (those past `count` are
// computed and ignored).
template <typename D, typename I>
[[gnu::always_inline]] inline void warp_light_lanes(WarpBlock& block, size_t count, double amount) {
  constexpr size_t kLanes = sizeof(D) / sizeof(double);
  static_assert(kWarpBlock % kLanes == 0);
  for (size_t first = 0; first < count; first += kLanes) {
    D kappa;
    std::memcpy(&kappa, block.kappa + first, sizeof kappa);
    const auto w = warp_lanes<D, I>(load_lanes<D>(block.wi, first), load_lanes<D>(block.r, first),
                                    kappa, amount);
    store_lanes(w, block.warped, first);
  }
}

COUNTERSHADE_AVX512_FUNCTION
void warp_light_avx512(WarpBlock& block, size_t count, double amount) {
  warp_light_lanes<WideLanes, WideLaneBits>(block, count, amount);
}

COUNTERSHADE_AVX2_CLONES
void warp_light_avx2(WarpBlock& block, size_t count, double amount) {
  warp_light_lanes<NarrowLanes, NarrowLaneBits>(block, count, amount);
}

void warp_light_block(WarpBlock& block, size_t count, double amount) {
  (has_avx512() ? warp_light_avx512 : warp_light_avx2)(block, count, amount);
}

}  // namespace

glm::dvec3 warp_light(const glm::dvec3& wi, const glm::dvec3& r, double kappa, double amount) {
  const Vec3Lanes<double> w =
      warp_lanes<double, int64_t>({wi.x, wi.y, wi.z}, {r.x, r.y, r.z}, kappa, amount);
  return {w.x, w.y, w.z};
}

void warp_lights(std::span<const glm::dvec3> wi, std::span<const glm::dvec3> r,
                 std::span<const double> kappa, double amount, glm::dvec3* out) {
  WarpBlock block;
  for (size_t first = 0; first < wi.size(); first += kWarpBlock) {
    const size_t count = std::min(kWarpBlock, wi.size() - first);
    for (size_t j = 0; j < count; ++j) {
      block.kappa[j] = kappa[first + j];
      for (int c = 0; c < 3; ++c) {
        block.wi[c][j] = wi[first + j][c];
        block.r[c][j] = r[first + j][c];
      }
    }
    warp_light_block(block, count, amount);
    for (size_t j = 0; j < count; ++j)
      out[first + j] = {block.warped[0][j], block.warped[1][j], block.warped[2][j]};
  }
}

namespace {

struct LwParameters final : MethodParameters {
  double alpha = 16.62;        // α: the amount of warping at λ = 1
  double tau = 1;              // τ, pixels: the scale of κ = tanh(τ·curvature)
  double terminator_fade = 0;  // ShadingHook::terminator_band
};

class LwHook final : public ShadingHook {
 public:
  LwHook(std::shared_ptr<const ViewCurvature> kappa, double amount, double band)
      : kappa_(std::move(kappa)), amount_(amount), band_(band) {}

  // The warp remaps the whole sphere of light directions around r, those below the surface's
  // horizon included: a light just behind the terminator may be turned in front of it, and is then
  // shaded like its neighbour just in front (with the warped direction's visibility). Keeping the
  // attached shadow instead would draw the terminator as an edge wherever the warp lifts the light.
  bool shades_dark_side() const override { return true; }
  std::optional<glm::dvec3> dark_side_direction(const ShadingInputs& s,
                                                const glm::dvec3& wi) const override {
    return warp_light(wi, reflected_view(s), kappa_->at(s.point.position), amount_);
  }
  double terminator_band() const override { return band_; }

  glm::dvec3 reflect(const ShadingInputs& s, const glm::dvec3& wi,
                     const glm::dvec3& incident) const override {
    return reflect_plain(
        s, warp_light(wi, reflected_view(s), kappa_->at(s.point.position), amount_), incident);
  }

  // The same, the warps computed in vector lanes (warp_lights).
  void reflect_many(std::span<const HookSample> samples, glm::dvec3* out) const override {
    thread_local std::vector<glm::dvec3> wi, r, warped;
    thread_local std::vector<double> kappa;
    wi.clear();
    r.clear();
    kappa.clear();
    for (const HookSample& sample : samples) {
      wi.push_back(sample.wi);
      r.push_back(reflected_view(*sample.inputs));
      kappa.push_back(kappa_->at(sample.inputs->point.position));
    }
    warped.resize(samples.size());
    warp_lights(wi, r, kappa, amount_, warped.data());
    for (size_t k = 0; k < samples.size(); ++k)
      out[k] = reflect_plain(*samples[k].inputs, warped[k], samples[k].incident);
  }

 private:
  static glm::dvec3 reflected_view(const ShadingInputs& s) {
    return 2 * glm::dot(s.normal, s.wo) * s.normal - s.wo;
  }

  std::shared_ptr<const ViewCurvature> kappa_;
  double amount_, band_;
};

class LwMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "light-warping"; }
  std::string summary() const override {
    return "light warping: light turned by view-dependent curvature (shading)";
  }
  MethodAxes axes() const override {
    return {"amount of warping λ·α (0 = plain, 1 = the given α)", {}};
  }
  std::vector<ParameterDoc> parameter_docs() const override {
    return {{"alpha", "16.62", "α: the amount of warping at λ = 1 (the exponent's factor on κ)"},
            curvature_tau_doc(),
            terminator_fade_doc()};
  }
  std::shared_ptr<const MethodParameters> parse(const ParameterBag& bag) const override {
    auto p = std::make_shared<LwParameters>();
    p->alpha = bag.number_in("alpha", 16.62, 0.0, 1000.0);
    p->tau = read_curvature_tau(bag);
    p->terminator_fade = read_terminator_fade(bag);
    bag.finish(name());
    return p;
  }
  RenderRequest request(const MethodParameters&) const override { return shading_request(); }
  std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                               const MethodParameters& parameters) const override {
    require_scene(context, name());
    const auto& p = parameters_as<LwParameters>(parameters);
    auto kappa = std::make_shared<const ViewCurvature>(*context.view, p.tau);
    auto hook_for = [kappa, p](double lambda) -> std::shared_ptr<const ShadingHook> {
      const double amount = lambda * p.alpha;
      return amount != 0 ? std::make_shared<LwHook>(kappa, amount, p.terminator_fade) : nullptr;
    };
    return std::make_unique<HookedRender>(
        context, hook_for,
        nlohmann::json{{"alpha", p.alpha}, {"tau", p.tau}, {"terminator_fade", p.terminator_fade}});
  }
};

}  // namespace

std::unique_ptr<const EnhancementMethod> make_light_warping_method() {
  return std::make_unique<LwMethod>();
}

}  // namespace countershade
