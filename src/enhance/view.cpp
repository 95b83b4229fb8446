#include "enhance/view.h"

#include "enhance/lightness.h"

namespace countershade {

void quantize_in_place(Image& image, int bits) {
  const float levels = float((1u << bits) - 1u);
  for (float& v : image.pixels) v = float(quantize(v, bits)) / levels;
}

std::shared_ptr<const View> make_view(std::shared_ptr<const Scene> scene, std::shared_ptr<const RayTracer> tracer,
                                      RenderResult render, int bits) {
  auto view = std::make_shared<View>();
  view->encoding = scene->display.encoding;
  view->bits = bits;
  view->display = encode_for_display(render.radiance, scene->display.exposure_stops, view->encoding);
  quantize_in_place(view->display, bits);
  view->lab = display_to_lab(view->display, view->encoding, bits);
  view->depth = render.gbuffer.depth;
  view->render = std::move(render);
  view->scene = std::move(scene);
  view->tracer = std::move(tracer);
  return view;
}

std::shared_ptr<const View> make_image_view(Image display, std::vector<float> depth, const DisplayEncoding& encoding,
                                            int bits) {
  auto view = std::make_shared<View>();
  view->encoding = encoding;
  view->bits = bits;
  view->display = std::move(display);
  quantize_in_place(view->display, bits);
  view->lab = display_to_lab(view->display, encoding, bits);
  view->depth = std::move(depth);
  return view;
}

void apply_request(Scene& scene, const RenderRequest& request) {
  if (request.refine_edge_length) refine_scene(scene, *request.refine_edge_length);
}

std::shared_ptr<const View> render_view(std::shared_ptr<const Scene> scene, const RenderRequest& request,
                                        const ViewOptions& options) {
  auto tracer = std::make_shared<const RayTracer>(*scene);
  RenderOptions ro;
  ro.threads = options.threads;
  ro.vertex_radiance = request.vertex_radiance;
  ro.ring_samples = request.ring_samples;
  ro.shading_hook = request.shading_hook;
  ro.texture_hook = request.texture_hook;
  ro.progress = options.progress;
  RenderResult result = render(*scene, *tracer, ro);
  return make_view(std::move(scene), std::move(tracer), std::move(result), options.bits);
}

}  // namespace countershade
