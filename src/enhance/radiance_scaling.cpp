// Radiance scaling (Vergne et al. 2010, 2011): each light sample's reflected radiance is multiplied
// by σ(κ, δ), which raises the contrast of shading on convex parts and lowers it on concave ones,
// from a view-dependent curvature κ of the base view's normals. α is the invariant point (a
// reflectance δ = α is never scaled), γ the strength, scaled by λ: λ = 0 is the plain render and
// λ = 1 the paper's setting (Mestres et al. 2021's Fig. 14: α = 0.5, γ = 4, isotropic curvature).
// Shadows are the plain ones (the shading hook).

#include "enhance/radiance_scaling.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>

#include "core/error.h"
#include "enhance/method.h"
#include "enhance/shading_method.h"
#include "enhance/view_curvature.h"
#include "render/shading.h"

namespace countershade {
namespace {

struct RsParameters final : MethodParameters {
  double alpha = 0.5;          // α: the invariant point
  double gamma = 4;            // γ: how strongly curvature scales, at λ = 1
  double tau = 1;              // τ, pixels: the scale of κ = tanh(τ·curvature)
  double terminator_fade = 0;  // ShadingHook::terminator_band
};

}  // namespace

// σ(κ, δ) = (α·e^{−γκ} + δ(1 − α(1 + e^{−γκ}))) / (α + δ(e^{−γκ} − α(1 + e^{−γκ}))); σ(0, δ) = 1,
// σ(κ, α) = 1.
double radiance_scale(double kappa, double delta, double alpha, double gamma) {
  const double e = std::exp(-gamma * kappa);
  const double numerator = alpha * e + delta * (1 - alpha * (1 + e));
  const double denominator = alpha + delta * (e - alpha * (1 + e));
  return denominator > 1e-12 ? numerator / denominator : 1.0;
}

namespace {

class RsHook final : public ShadingHook {
 public:
  RsHook(std::shared_ptr<const ViewCurvature> kappa, double alpha, double gamma, double band)
      : kappa_(std::move(kappa)), alpha_(alpha), gamma_(gamma), band_(band) {}

  // Radiance scaling scales the light that reaches the point: the attached shadow stays dark.
  double terminator_band() const override { return band_; }

  glm::dvec3 reflect(const ShadingInputs& s, const glm::dvec3& wi,
                     const glm::dvec3& incident) const override {
    const double kappa = kappa_->at(s.point.position);
    const double delta = std::max(0.0, glm::dot(s.normal, wi));
    return reflect_plain(s, wi, incident) * radiance_scale(kappa, delta, alpha_, gamma_);
  }

 private:
  std::shared_ptr<const ViewCurvature> kappa_;
  double alpha_, gamma_, band_;
};

class RsMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "radiance-scaling"; }
  std::string summary() const override {
    return "radiance scaling: light scaled by view-dependent curvature (shading)";
  }
  MethodAxes axes() const override { return {"strength λ·γ (0 = plain, 1 = the given γ)", {}}; }
  std::vector<ParameterDoc> parameter_docs() const override {
    return {{"alpha", "0.5",
             "α: the invariant point, the reflectance δ that is never scaled (in (0, 1))"},
            {"gamma", "4", "γ: how strongly curvature scales the light at λ = 1"},
            curvature_tau_doc(),
            terminator_fade_doc()};
  }
  std::shared_ptr<const MethodParameters> parse(const ParameterBag& bag) const override {
    auto p = std::make_shared<RsParameters>();
    p->alpha = bag.number("alpha", 0.5);
    if (!(p->alpha > 0 && p->alpha < 1))
      bag.fail("alpha", "the invariant point must lie in (0, 1)");
    p->gamma = bag.number_in("gamma", 4.0, 0.0, 50.0);
    p->tau = read_curvature_tau(bag);
    p->terminator_fade = read_terminator_fade(bag);
    bag.finish(name());
    return p;
  }
  RenderRequest request(const MethodParameters&) const override { return shading_request(); }
  std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                               const MethodParameters& parameters) const override {
    require_scene(context, name());
    const auto& p = parameters_as<RsParameters>(parameters);
    auto kappa = std::make_shared<const ViewCurvature>(*context.view, p.tau);
    auto hook_for = [p, kappa](double lambda) -> std::shared_ptr<const ShadingHook> {
      const double gamma = lambda * p.gamma;
      return gamma != 0 ? std::make_shared<RsHook>(kappa, p.alpha, gamma, p.terminator_fade)
                        : nullptr;
    };
    return std::make_unique<HookedRender>(context, hook_for,
                                          nlohmann::json{{"alpha", p.alpha},
                                                         {"gamma", p.gamma},
                                                         {"tau", p.tau},
                                                         {"terminator_fade", p.terminator_fade}});
  }
};

}  // namespace

std::unique_ptr<const EnhancementMethod> make_radiance_scaling_method() {
  return std::make_unique<RsMethod>();
}

}  // namespace countershade
