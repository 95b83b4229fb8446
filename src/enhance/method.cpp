#include "enhance/method.h"

#include <cmath>

#include "enhance/cornsweet.h"
#include "enhance/depth_usm.h"
#include "enhance/none.h"
#include "enhance/usm2d.h"
#include "enhance/usm3d.h"

namespace countershade {

void quantize_in_place(Image& image, int bits) {
  const float levels = float((1u << bits) - 1u);
  for (float& v : image.pixels) v = float(quantize(v, bits)) / levels;
}

View make_view(const Scene& scene, RenderResult render, int bits) {
  View view;
  view.scene = &scene;
  view.encoding = scene.display.encoding;
  view.bits = bits;
  view.display = encode_for_display(render.radiance, scene.display);
  quantize_in_place(view.display, bits);
  view.lab = display_to_lab(view.display, view.encoding);
  view.depth = render.gbuffer.depth;
  view.render = std::move(render);
  return view;
}

View make_image_view(Image display, std::vector<float> depth, const DisplayEncoding& encoding, int bits) {
  View view;
  view.encoding = encoding;
  view.bits = bits;
  view.display = std::move(display);
  quantize_in_place(view.display, bits);
  view.lab = display_to_lab(view.display, encoding);
  view.depth = std::move(depth);
  return view;
}

double image_sigma_px(const MethodOptions& o, int width, int height) {
  double diagonal = std::hypot(double(width), double(height));
  if (o.sigma_px) return *o.sigma_px;
  if (o.sigma_percent) return *o.sigma_percent / 100.0 * diagonal;
  if (o.kernel_percent) return *o.kernel_percent / 100.0 * diagonal / 4.0;
  return 0.0;
}

namespace {

// The registry: one entry per method.
const std::vector<const EnhancementMethod*>& registry() {
  static const NoEnhancement none;
  static const Usm3dMethod usm3d;
  static const Usm2dMethod usm2d;
  static const DepthUsmMethod depth_usm;
  static const CornsweetMethod cornsweet;
  static const std::vector<const EnhancementMethod*> methods = {&none, &usm3d, &usm2d, &depth_usm, &cornsweet};
  return methods;
}

}  // namespace

const EnhancementMethod* find_method(const std::string& name) {
  for (const EnhancementMethod* m : registry())
    if (m->name() == name) return m;
  return nullptr;
}

std::vector<std::string> method_names() {
  std::vector<std::string> names;
  for (const EnhancementMethod* m : registry()) names.push_back(m->name());
  return names;
}

}  // namespace countershade
