#include "enhance/shading_method.h"

#include "core/error.h"

namespace countershade {

NormalScales read_normal_scales(const ParameterBag& bag, std::optional<double>& sigma) {
  NormalScales s;
  sigma = bag.optional_number("sigma");
  s.scales = int(bag.integer_in("scales", 3, 2, kMaxNormalScales));
  return s;
}

void check_normal_scales(const ParameterBag& bag, NormalScales& scales, const std::optional<double>& sigma) {
  if (!sigma || !(*sigma > 0)) bag.fail("sigma", "is required: the finest smoothing width, a positive world length");
  scales.sigma = *sigma;
}

WidthAxis normal_scales_axis() {
  return {"sigma", "world units", "the finest smoothing width σ_1 of the normals (scale k+1 smooths over σ_1·1.7^(k−1))"};
}

std::vector<ParameterDoc> normal_scales_docs() {
  return {{"sigma", "", "finest smoothing width σ_1 of the normals, world units"},
          {"scales", "3", "number of normal scales S (2 to 8)"}};
}

RenderRequest shading_request() {
  RenderRequest r;
  r.scene = true;
  return r;
}

void require_scene(const PrepareContext& context, const std::string& method) {
  if (!context.render_again) throw InputError(method + " changes the shading of a rendered scene; it needs a scene");
}

std::shared_ptr<const MultiscaleNormals> scene_normals(const PrepareContext& context, const NormalScales& scales,
                                                       const std::string& method) {
  require_scene(context, method);
  return std::make_shared<const MultiscaleNormals>(context.view->scene, scales.sigma, scales.scales, context.threads);
}

Composed HookedRender::compose(double lambda) const {
  std::shared_ptr<const ShadingHook> hook = hook_for_(lambda);
  if (!hook) return {view_->display, 0};
  RenderRequest request;
  request.scene = true;
  request.shading_hook = std::move(hook);
  return {render_again_(request)->display, 0};
}

}  // namespace countershade
