// Radiance scaling (Vergne et al. 2010): each light sample's reflected radiance is multiplied by
// σ(κ, δ), which raises the contrast of shading on convex parts and lowers the radiance of lit
// concave parts, from a view-dependent curvature κ of the base view's normals. α = clamp(λ, 0, 1);
// λ = 0 is the plain render. Shadows are the plain ones (the shading hook).

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "enhance/method.h"
#include "enhance/radiance_scaling.h"
#include "enhance/shading_method.h"
#include "render/camera.h"
#include "render/shading.h"

namespace countershade {
namespace {

struct RsParameters final : MethodParameters {
  double gamma = 1;  // γ: how strongly curvature scales
  double tau = 1;    // τ, pixels: the scale of κ = tanh(τ·curvature)
};

}  // namespace

// σ(κ, δ) = (α·e^{−γκ} + δ(1 − α(1 + e^{−γκ}))) / (α + δ(e^{−γκ} − α(1 + e^{−γκ}))); σ(0, δ) = 1.
double radiance_scale(double kappa, double delta, double alpha, double gamma) {
  const double e = std::exp(-gamma * kappa);
  const double numerator = alpha * e + delta * (1 - alpha * (1 + e));
  const double denominator = alpha + delta * (e - alpha * (1 + e));
  return denominator > 1e-12 ? numerator / denominator : 1.0;
}

// κ per pixel of the view: tanh(−τ·div g) of the screen gradient field g = −(n_x, n_y)/n_z of the
// view-space normals (central differences in pixels; 0 where a neighbour is background), so that
// κ > 0 on convex and κ < 0 on concave parts. Background pixels are 0.
Image view_curvature(const View& view, double tau) {
  const GBuffer& g = view.render.gbuffer;
  const CameraRays camera(view.scene->camera);
  std::vector<glm::dvec2> field(g.normal.size(), glm::dvec2(0.0));
  std::vector<char> valid(g.normal.size(), 0);
  for (size_t i = 0; i < field.size(); ++i) {
    if (g.object[i] < 0) continue;
    const glm::dvec3 n(g.normal[i]);
    const double nz = std::max(-glm::dot(n, camera.forward()), 1e-3);
    field[i] = -glm::dvec2(glm::dot(n, camera.right()), glm::dot(n, camera.up())) / nz;
    valid[i] = 1;
  }
  Image kappa(g.width, g.height, 1);
  for (int y = 1; y + 1 < g.height; ++y)
    for (int x = 1; x + 1 < g.width; ++x) {
      const size_t i = g.index(x, y), l = i - 1, r = i + 1, above = i - size_t(g.width), below = i + size_t(g.width);
      if (!valid[i] || !valid[l] || !valid[r] || !valid[above] || !valid[below]) continue;
      // Film rows grow downwards while the view's y axis points up.
      const double divergence = 0.5 * (field[r].x - field[l].x) + 0.5 * (field[above].y - field[below].y);
      kappa.at(x, y) = float(std::tanh(-tau * divergence));
    }
  return kappa;
}

namespace {

class RsHook final : public ShadingHook {
 public:
  RsHook(std::shared_ptr<const Image> kappa, const Camera& camera, double alpha, double gamma)
      : kappa_(std::move(kappa)), camera_(camera), alpha_(alpha), gamma_(gamma) {}

  glm::dvec3 reflect(const ShadingInputs& s, const glm::dvec3& wi, const glm::dvec3& incident) const override {
    const glm::dvec2 film = camera_.film_position(s.point.position);
    const int x = std::clamp(int(std::floor(film.x)), 0, kappa_->width - 1);
    const int y = std::clamp(int(std::floor(film.y)), 0, kappa_->height - 1);
    const double delta = std::max(0.0, glm::dot(s.normal, wi));
    return reflect_plain(s, wi, incident) * radiance_scale(kappa_->at(x, y), delta, alpha_, gamma_);
  }

 private:
  std::shared_ptr<const Image> kappa_;
  CameraRays camera_;
  double alpha_, gamma_;
};

class RsMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "radiance-scaling"; }
  std::string summary() const override { return "radiance scaling: light scaled by view-dependent curvature (shading)"; }
  MethodAxes axes() const override { return {"enhancement α = clamp(λ, 0, 1)", {}}; }
  std::vector<ParameterDoc> parameter_docs() const override {
    return {{"gamma", "1", "γ: how strongly curvature scales the light"},
            {"tau", "1", "τ in pixels: κ = tanh(τ·curvature of the screen-space normal field)"}};
  }
  std::shared_ptr<const MethodParameters> parse(const ParameterBag& bag) const override {
    auto p = std::make_shared<RsParameters>();
    p->gamma = bag.number_in("gamma", 1.0, 0.0, 50.0);
    p->tau = bag.number_in("tau", 1.0, 0.0, 1e6);
    bag.finish(name());
    return p;
  }
  RenderRequest request(const MethodParameters&) const override { return shading_request(); }
  std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                               const MethodParameters& parameters) const override {
    require_scene(context, name());
    const auto& p = parameters_as<RsParameters>(parameters);
    auto kappa = std::make_shared<const Image>(view_curvature(*context.view, p.tau));
    auto hook_for = [p, kappa, camera = context.view->scene->camera](double lambda) -> std::shared_ptr<const ShadingHook> {
      const double alpha = std::clamp(lambda, 0.0, 1.0);
      return alpha > 0 ? std::make_shared<RsHook>(kappa, camera, alpha, p.gamma) : nullptr;
    };
    return std::make_unique<HookedRender>(context, hook_for, nlohmann::json{{"gamma", p.gamma}, {"tau", p.tau}});
  }
};

}  // namespace

std::unique_ptr<const EnhancementMethod> make_radiance_scaling_method() { return std::make_unique<RsMethod>(); }

}  // namespace countershade
