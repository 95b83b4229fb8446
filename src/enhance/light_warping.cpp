// Light warping (Vergne et al. 2009), as methods.md reads it: every light sample's direction is
// turned towards the view-reflected direction on convex parts and away from it on concave parts,
// by the view curvature κ of radiance scaling. λ = 0 is the plain render; shadows are the plain
// ones (the shading hook).

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "enhance/light_warping.h"
#include "enhance/method.h"
#include "enhance/shading_method.h"
#include "enhance/view_curvature.h"
#include "render/shading.h"

namespace countershade {

glm::dvec3 warp_light(const glm::dvec3& wi, const glm::dvec3& r, double kappa, double lambda) {
  const double cos_angle = std::clamp(glm::dot(wi, r), -1.0, 1.0);
  const glm::dvec3 across = wi - cos_angle * r;  // wi's part perpendicular to r
  const double across_length = glm::length(across);
  if (across_length < 1e-12) return wi;  // along r or opposite it: the warp keeps both
  const double angle = std::acos(cos_angle);
  const double e = std::exp(-lambda * kappa);
  const double warped = angle * e / (1 + (e - 1) * angle / M_PI);
  return std::cos(warped) * r + std::sin(warped) * (across / across_length);
}

namespace {

struct LwParameters final : MethodParameters {
  double tau = 1;  // τ, pixels: the scale of κ = tanh(τ·curvature)
};

class LwHook final : public ShadingHook {
 public:
  LwHook(std::shared_ptr<const ViewCurvature> kappa, double lambda) : kappa_(std::move(kappa)), lambda_(lambda) {}

  glm::dvec3 reflect(const ShadingInputs& s, const glm::dvec3& wi, const glm::dvec3& incident) const override {
    const double kappa = kappa_->at(s.point.position);
    const glm::dvec3 r = 2 * glm::dot(s.normal, s.wo) * s.normal - s.wo;
    return reflect_plain(s, warp_light(wi, r, kappa, lambda_), incident);
  }

 private:
  std::shared_ptr<const ViewCurvature> kappa_;
  double lambda_;
};

class LwMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "light-warping"; }
  std::string summary() const override { return "light warping: light turned by view-dependent curvature (shading)"; }
  MethodAxes axes() const override { return {"warp strength λ (0 = plain)", {}}; }
  std::vector<ParameterDoc> parameter_docs() const override {
    return {curvature_tau_doc()};
  }
  std::shared_ptr<const MethodParameters> parse(const ParameterBag& bag) const override {
    auto p = std::make_shared<LwParameters>();
    p->tau = read_curvature_tau(bag);
    bag.finish(name());
    return p;
  }
  RenderRequest request(const MethodParameters&) const override { return shading_request(); }
  std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                               const MethodParameters& parameters) const override {
    require_scene(context, name());
    const auto& p = parameters_as<LwParameters>(parameters);
    auto kappa = std::make_shared<const ViewCurvature>(*context.view, p.tau);
    auto hook_for = [kappa](double lambda) -> std::shared_ptr<const ShadingHook> {
      return lambda != 0 ? std::make_shared<LwHook>(kappa, lambda) : nullptr;
    };
    return std::make_unique<HookedRender>(context, hook_for, nlohmann::json{{"tau", p.tau}});
  }
};

}  // namespace

std::unique_ptr<const EnhancementMethod> make_light_warping_method() { return std::make_unique<LwMethod>(); }

}  // namespace countershade
