#include "enhance/method.h"

#include "render/renderer.h"

namespace countershade {

PrepareContext make_use_context(std::shared_ptr<const View> view, size_t use, int threads) {
  PrepareContext context = make_context(std::move(view), threads);
  context.stage = context.view->stages.at(use);
  for (size_t f : context.view->stage_fields.at(use))
    context.fields.push_back(&context.view->render.fields.at(f));
  if (const int change = context.view->change_noise.at(use); change >= 0)
    context.change_noise = &context.view->render.change_noise.at(size_t(change));
  return context;
}

PrepareContext make_context(std::shared_ptr<const View> view, int threads) {
  PrepareContext context;
  context.threads = threads;
  if (view->scene) {
    context.render_again = [scene = view->scene, tracer = view->tracer, bits = view->bits,
                            trace = view->render.trace, threads](const RenderRequest& request) {
      RenderOptions options;
      options.replay_trace =
          trace;  // same scene and camera: the hooks re-shade, nothing is traced again
      options.threads = threads;
      options.vertex_radiance = request.vertex_radiance;
      options.ring_samples = request.ring_samples;
      options.shading_hook = request.shading_hook;
      options.texture_hook = request.texture_hook;
      options.estimate_noise = false;  // the method keeps the display only
      options.radiance_only = true;
      return make_view(scene, tracer, render(*scene, *tracer, options), bits, false);
    };
  }
  context.view = std::move(view);
  return context;
}

}  // namespace countershade
