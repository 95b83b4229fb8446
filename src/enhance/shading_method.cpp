#include "enhance/shading_method.h"

#include "core/error.h"
#include "enhance/image_normals.h"

namespace countershade {

NormalScales read_normal_scales(const ParameterBag& bag, std::optional<double>& sigma) {
  NormalScales s;
  sigma = bag.optional_number("sigma");
  s.scales = int(bag.integer_in("scales", 3, 2, kMaxNormalScales));
  s.image = bag.choice("mode", "surface", {"surface", "image"}) == "image";
  if (bag.has("depth_tolerance") && !s.image)
    bag.fail("depth_tolerance", "applies to mode image only");
  s.depth_tolerance = bag.number_in("depth_tolerance", 0.02, 1e-6, 10.0);
  return s;
}

void check_normal_scales(const ParameterBag& bag, NormalScales& scales,
                         const std::optional<double>& sigma) {
  if (!sigma || !(*sigma > 0))
    bag.fail("sigma", scales.image
                          ? "is required: the finest filter width, a positive number of pixels"
                          : "is required: the finest smoothing width, a positive world length");
  if (scales.image && *sigma > 1000) bag.fail("sigma", "must be at most 1000 pixels");
  scales.sigma = *sigma;
}

WidthAxis normal_scales_axis() {
  return {"sigma", "world units (pixels with mode image)",
          "the finest smoothing width σ_1 of the normals (scale k+1 smooths over σ_1·1.7^(k−1))"};
}

std::vector<ParameterDoc> normal_scales_docs() {
  return {{"sigma", "",
           "finest smoothing width σ_1 of the normals, world units (pixels with mode image)"},
          {"scales", "3", "number of normal scales S (2 to 8)"},
          {"mode", "surface",
           "surface: normals smoothed over the mesh (view-independent); image: G-buffer normals, "
           "bilateral-filtered with a depth range kernel (the paper's, changes with the view)"},
          {"depth_tolerance", "0.02",
           "image mode: the range kernel's σ as a fraction of the pixel's depth"}};
}

double read_terminator_fade(const ParameterBag& bag) {
  return bag.number_in("terminator_fade", 0.0, 0.0, 1.0);
}

ParameterDoc terminator_fade_doc() {
  return {"terminator_fade", "0",
          "cosine band (0 to 1) over which the change fades out towards the original light's "
          "terminator, hiding "
          "facet steps there; with a band the original light's dark side stays dark (0: no fade)"};
}

RenderRequest shading_request() {
  RenderRequest r;
  r.scene = true;
  r.renders_again = true;
  return r;
}

void require_scene(const PrepareContext& context, const std::string& method) {
  if (!context.render_again)
    throw InputError(method + " changes the shading of a rendered scene; it needs a scene");
}

std::shared_ptr<const NormalScaleField> scene_normals(const PrepareContext& context,
                                                      const NormalScales& scales,
                                                      const std::string& method) {
  require_scene(context, method);
  if (scales.image)
    return std::make_shared<const ImageNormals>(*context.view, scales.sigma, scales.scales,
                                                scales.depth_tolerance, context.threads);
  return MultiscaleNormals::shared(context.view->scene, scales.sigma, scales.scales,
                                   context.threads);
}

nlohmann::json describe_normals(const NormalScales& scales, const NormalScaleField& normals) {
  nlohmann::json out = normals.describe();
  out["scales"] = scales.scales;
  return out;
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
