// Local light alignment (Mestres et al. 2021): per shading point, the light direction is rotated
// from the coarsest scale of the normal field to the finest, so that every feature gets a lit and
// an unlit side (enhance/light_alignment.h). Diffuse shading is guided by the multi-scale normals,
// specular shading by the reflected view vectors. Visibility stays that of the original light
// (the shading hook). `surface` mode: the normals are smoothed over the mesh
// (enhance/multiscale_normals.h). λ scales the per-scale strengths: s_i = clamp(λ·profile_i, 0, 1).

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "core/error.h"
#include "enhance/light_alignment.h"
#include "enhance/method.h"
#include "enhance/multiscale_normals.h"
#include "render/shading.h"

namespace countershade {
namespace {

constexpr int kMaxScales = 8;

struct LlaParameters final : MethodParameters {
  double sigma = 0;            // σ_1, the finest smoothing width, world units
  int scales = 3;              // S
  double gamma = 3;            // W_γ
  std::vector<double> profile;  // ŝ_1 … ŝ_{S−1}
};

// Shades every light sample with the light aligned per point: the diffuse term towards the
// multi-scale normals, the specular term towards the reflected view vectors.
class AlignmentHook final : public ShadingHook {
 public:
  AlignmentHook(std::shared_ptr<const MultiscaleNormals> normals, std::vector<double> strengths, double gamma)
      : normals_(std::move(normals)), strengths_(std::move(strengths)), gamma_(gamma) {}

  glm::dvec3 reflect(const ShadingInputs& s, const glm::dvec3& wi, const glm::dvec3& incident) const override {
    glm::dvec3 n[kMaxScales], r[kMaxScales];
    const int scales = normals_->scales();
    // The smoothed normals on the side the viewer sees, as the shading normal is.
    const double side = glm::dot(s.normal, s.point.shading_normal) < 0 ? -1.0 : 1.0;
    n[0] = s.normal;
    for (int k = 2; k <= scales; ++k) n[k - 1] = side * normals_->at(s.point, k);
    for (int k = 0; k < scales; ++k) r[k] = 2 * glm::dot(n[k], s.wo) * n[k] - s.wo;
    const std::span<const glm::dvec3> normal_scales(n, size_t(scales)), view_scales(r, size_t(scales));
    const glm::dvec3 diffuse_light = align_light(wi, normal_scales, strengths_, gamma_);
    const glm::dvec3 specular_light = align_light(wi, view_scales, strengths_, gamma_);
    return reflect_diffuse(s, diffuse_light, incident) + reflect_specular(s, specular_light, incident);
  }

 private:
  std::shared_ptr<const MultiscaleNormals> normals_;
  std::vector<double> strengths_;
  double gamma_;
};

class PreparedLla final : public PreparedEnhancement {
 public:
  PreparedLla(const PrepareContext& context, const LlaParameters& p, std::shared_ptr<const MultiscaleNormals> normals)
      : view_(context.view), render_again_(context.render_again), parameters_(p), normals_(std::move(normals)) {}

  // Every λ is a render with the aligned light; with all strengths 0 it is the view itself.
  Composed compose(double lambda) const override {
    std::vector<double> strengths;
    for (double s : parameters_.profile) strengths.push_back(std::clamp(lambda * s, 0.0, 1.0));
    if (std::all_of(strengths.begin(), strengths.end(), [](double s) { return s <= 0; })) return {view_->display, 0};
    RenderRequest request;
    request.scene = true;
    request.shading_hook = std::make_shared<AlignmentHook>(normals_, std::move(strengths), parameters_.gamma);
    return {render_again_(request)->display, 0};
  }

  nlohmann::json parameters() const override {
    nlohmann::json iterations = nlohmann::json::array();
    for (size_t o = 0; o < view_->scene->objects.size(); ++o)
      for (int k = 2; k <= parameters_.scales; ++k) iterations.push_back(normals_->iterations(o, k));
    return {{"scales", parameters_.scales}, {"gamma", parameters_.gamma}, {"profile", parameters_.profile},
            {"smoothing_iterations", iterations}};
  }

 private:
  std::shared_ptr<const View> view_;
  std::function<std::shared_ptr<const View>(const RenderRequest&)> render_again_;
  LlaParameters parameters_;
  std::shared_ptr<const MultiscaleNormals> normals_;
};

class LlaMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "lla"; }
  std::string summary() const override { return "local light alignment: the light turned per point to reveal shape (shading)"; }
  MethodAxes axes() const override {
    return {"per-scale strength s_i = clamp(λ·profile_i, 0, 1)",
            {{"sigma", "world units", "the finest smoothing width σ_1 of the normals (scale k+1 smooths over σ_1·1.7^(k−1))"}}};
  }
  std::vector<ParameterDoc> parameter_docs() const override {
    return {{"sigma", "", "finest smoothing width σ_1 of the normals, world units"},
            {"scales", "3", "number of normal scales S (2 to 8); S − 1 rotations"},
            {"gamma", "3", "γ of the weight W_γ: larger values sharpen the lit/unlit transitions"},
            {"profile", "all 1", "S − 1 strengths in [0, 1], finest first, scaled by λ"}};
  }

  std::shared_ptr<const MethodParameters> parse(const ParameterBag& bag) const override {
    auto p = std::make_shared<LlaParameters>();
    const std::optional<double> sigma = bag.optional_number("sigma");
    p->scales = int(bag.integer_in("scales", 3, 2, kMaxScales));
    p->gamma = bag.number_in("gamma", 3.0, 0.0, 50.0);
    p->profile = bag.numbers("profile", std::vector<double>(size_t(p->scales - 1), 1.0));
    bag.finish(name());
    if (!sigma || !(*sigma > 0)) bag.fail("sigma", "is required: the finest smoothing width, a positive world length");
    p->sigma = *sigma;
    if (p->profile.size() != size_t(p->scales - 1))
      bag.fail("profile", "needs " + std::to_string(p->scales - 1) + " values (one per rotation, finest first)");
    for (double s : p->profile)
      if (!(s >= 0 && s <= 1)) bag.fail("profile", "values must be in [0, 1]");
    return p;
  }

  RenderRequest request(const MethodParameters&) const override {
    RenderRequest r;
    r.scene = true;
    return r;
  }

  std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                               const MethodParameters& parameters) const override {
    if (!context.render_again) throw InputError("lla changes the shading of a rendered scene; it needs a scene");
    const auto& p = parameters_as<LlaParameters>(parameters);
    auto normals = std::make_shared<const MultiscaleNormals>(context.view->scene, p.sigma, p.scales, context.threads);
    return std::make_unique<PreparedLla>(context, p, std::move(normals));
  }
};

}  // namespace

std::unique_ptr<const EnhancementMethod> make_lla_method() { return std::make_unique<LlaMethod>(); }

}  // namespace countershade
