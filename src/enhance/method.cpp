#include "enhance/method.h"

#include "core/error.h"
#include "enhance/registry.h"

namespace countershade {

PrepareContext make_context(std::shared_ptr<const View> view, int threads) {
  PrepareContext context;
  context.threads = threads;
  if (view->scene) {
    context.render_again = [scene = view->scene, tracer = view->tracer, bits = view->bits,
                            threads](const RenderRequest& request) {
      RenderOptions options;
      options.threads = threads;
      options.vertex_radiance = request.vertex_radiance;
      options.ring_samples = request.ring_samples;
      options.shading_hook = request.shading_hook;
      options.texture_hook = request.texture_hook;
      return make_view(scene, tracer, render(*scene, *tracer, options), bits);
    };
  }
  context.view = std::move(view);
  return context;
}

std::unique_ptr<PreparedEnhancement> prepare_method(const std::string& method, std::shared_ptr<const View> view,
                                                    const nlohmann::json& parameters, int threads) {
  const EnhancementMethod& m = method_named(method, "method");
  auto parsed = m.parse(ParameterBag::from_json(parameters, method, "parameters"));
  return m.prepare(make_context(std::move(view), threads), *parsed);
}

}  // namespace countershade
