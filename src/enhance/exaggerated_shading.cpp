// Exaggerated shading (Rusinkiewicz et al. 2006), in countershade's surface mode: the diffuse term
// of every light sample is replaced by a half-Lambertian, multi-scale shading in which the light
// grazes each coarser scale of the surface, so that detail at every scale shows. The scales'
// weights follow the paper's default k_i ∝ σ_i^−0.5. λ blends the plain render (0) and
// exaggerated shading (1). Specular shading and cast shadows are the plain ones.
// The half-Lambertian term has no dark side: behind the original light's terminator a point keeps
// it wherever the light mirrored across its tangent plane is open (docs/enhancement-methods.md).

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <numbers>

#include "core/error.h"
#include "enhance/method.h"
#include "enhance/multiscale_normals.h"
#include "enhance/normal_field.h"
#include "enhance/shading_method.h"
#include "render/shading.h"

namespace countershade {
namespace {

struct EsParameters final : MethodParameters {
  NormalScales normals;         // σ_1 and S
  double contrast = 2;          // a
  std::vector<double> weights;  // k_1 … k_{S−1}, then k_b; they sum to 1 (power_weights by default)
  double terminator_fade = 0;  // ShadingHook::terminator_band
};

// Σ_i k_i·c_i + k_b·(½ + ½·n_S·l), c_i = ½ + ½·clamp(a·n_i·l_{i+1}, −1, 1), where l_{i+1} is the
// light projected onto the plane across n_{i+1} (it grazes the coarser surface).
double exaggerated(const glm::dvec3* n, int scales, const glm::dvec3& light,
                   const EsParameters& p) {
  double shade = 0;
  for (int i = 0; i + 1 < scales; ++i) {
    const glm::dvec3 coarser = n[i + 1];
    glm::dvec3 grazing = light - coarser * glm::dot(light, coarser);
    const double length = glm::length(grazing);
    if (length < 1e-12)
      grazing = glm::dvec3(0.0);  // light along the coarser normal: no grazing direction
    else
      grazing /= length;
    shade += p.weights[size_t(i)] *
             (0.5 + 0.5 * std::clamp(p.contrast * glm::dot(n[i], grazing), -1.0, 1.0));
  }
  return shade + p.weights.back() * (0.5 + 0.5 * glm::dot(n[scales - 1], light));
}

// k_i ∝ σ_i^P, i = 1 … S (the base coat last), σ_i = σ_1·1.7^(i−1), summing to 1. Rusinkiewicz et
// al. give the pass of scale i the width of its finer normals and the base coat the next width;
// countershade's finest normal is the unsmoothed one, so pass i takes the width σ_i that
// separates it from the next. Either way the widths grow by 1.7 a scale, and the normalised
// weights depend on that ratio alone.
std::vector<double> power_weights(int scales, double power) {
  std::vector<double> k(static_cast<size_t>(scales));
  double sum = 0;
  for (int i = 0; i < scales; ++i) sum += k[size_t(i)] = std::pow(kNormalScaleRatio, power * i);
  for (double& w : k) w /= sum;
  return k;
}

void check_weights(const ParameterBag& bag, const std::vector<double>& weights, int scales) {
  if (weights.size() != size_t(scales))
    bag.fail("weights", "needs " + std::to_string(scales) + " values");
  double sum = 0;
  for (double k : weights) {
    if (!(k >= 0)) bag.fail("weights", "must not be negative");
    sum += k;
  }
  if (std::abs(sum - 1) > 1e-9) bag.fail("weights", "must sum to 1");
}

class EsHook final : public ShadingHook {
 public:
  EsHook(std::shared_ptr<const NormalScaleField> normals, EsParameters parameters, double blend)
      : normals_(std::move(normals)), parameters_(std::move(parameters)), blend_(blend) {}

  glm::dvec3 reflect(const ShadingInputs& s, const glm::dvec3& wi,
                     const glm::dvec3& incident) const override {
    glm::dvec3 n[kMaxNormalScales];
    normals_->at_shading_point(s, n);
    const glm::dvec3 diffuse = s.albedo / std::numbers::pi * incident *
                               exaggerated(n, normals_->scales(), wi, parameters_);
    const glm::dvec3 enhanced = diffuse + reflect_specular(s, wi, incident);
    return (1 - blend_) * reflect_plain(s, wi, incident) + blend_ * enhanced;
  }

  // The half-Lambertian term has no single light direction. Its visibility on the dark side is
  // tested along the light mirrored across the tangent plane: the same angle above the surface
  // as the light is below it, so the test meets the original shadow ray at the terminator.
  bool shades_dark_side() const override { return true; }
  std::optional<glm::dvec3> dark_side_direction(const ShadingInputs& s,
                                                const glm::dvec3& wi) const override {
    return wi - 2 * glm::dot(s.normal, wi) * s.normal;
  }
  double terminator_band() const override { return parameters_.terminator_fade; }

 private:
  std::shared_ptr<const NormalScaleField> normals_;
  EsParameters parameters_;
  double blend_;
};

class EsMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "exaggerated-shading"; }
  std::string summary() const override {
    return "exaggerated shading: half-Lambertian multi-scale shading (shading)";
  }
  MethodAxes axes() const override {
    return {"blend from the plain render (0) to exaggerated shading (1), clamped to [0, 1]",
            {normal_scales_axis()}};
  }
  std::vector<ParameterDoc> parameter_docs() const override {
    std::vector<ParameterDoc> docs = normal_scales_docs();
    docs.push_back({"contrast", "2", "the contrast a of each scale's term"});
    docs.push_back({"weight_power", "-0.5",
                    "k_i ∝ σ_i^P over the scales' widths σ_1·1.7^(i−1), base last, summing to 1 "
                    "(the paper's default "
                    "−0.5; 0: equal weights)"});
    docs.push_back(
        {"weights", "",
         "S explicit weights k_1 … k_{S−1}, k_b (finest first, the base last) summing to 1, "
         "in place of weight_power"});
    docs.push_back(terminator_fade_doc());
    return docs;
  }
  std::shared_ptr<const MethodParameters> parse(const ParameterBag& bag) const override {
    auto p = std::make_shared<EsParameters>();
    std::optional<double> sigma;
    p->normals = read_normal_scales(bag, sigma);
    const int scales = p->normals.scales;
    p->contrast = bag.number_in("contrast", 2.0, 0.0, 100.0);
    if (bag.has("weights") && bag.has("weight_power"))
      bag.fail("weight_power", "give weights or weight_power, not both");
    const double power = bag.number_in("weight_power", -0.5, -8.0, 8.0);
    p->weights = bag.numbers("weights", power_weights(scales, power));
    p->terminator_fade = read_terminator_fade(bag);
    bag.finish(name());
    check_normal_scales(bag, p->normals, sigma);
    check_weights(bag, p->weights, scales);
    return p;
  }
  RenderRequest request(const MethodParameters&) const override { return shading_request(); }
  // λ in [0, 1] blends the plain render and exaggerated shading; λ ≤ 0 is the view itself.
  std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                               const MethodParameters& parameters) const override {
    const auto& p = parameters_as<EsParameters>(parameters);
    auto normals = scene_normals(context, p.normals, name());
    auto hook_for = [p, normals](double lambda) -> std::shared_ptr<const ShadingHook> {
      const double blend = std::clamp(lambda, 0.0, 1.0);
      return blend > 0 ? std::make_shared<EsHook>(normals, p, blend) : nullptr;
    };
    nlohmann::json recorded = describe_normals(p.normals, *normals);
    recorded["contrast"] = p.contrast;
    recorded["weights"] = p.weights;
    recorded["terminator_fade"] = p.terminator_fade;
    return std::make_unique<HookedRender>(context, hook_for, recorded);
  }
};

}  // namespace

std::unique_ptr<const EnhancementMethod> make_exaggerated_shading_method() {
  return std::make_unique<EsMethod>();
}

}  // namespace countershade
