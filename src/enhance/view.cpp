#include "enhance/view.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/code_quantizer.h"
#include "enhance/display_lab.h"

namespace countershade {

void quantize_in_place(Image& image, int bits) {
  const float levels = float((1u << bits) - 1u);
  for (float& v : image.pixels) v = float(quantize(v, bits)) / levels;
}

namespace {

// encode_for_display and then quantize_in_place, in one pass without a pow() per channel.
Image quantized_display(const Image& radiance, const Exposure& exposure,
                        const DisplayEncoding& encoding, int bits) {
  const CodeQuantizer& quantizer = CodeQuantizer::shared(encoding, bits);
  Image out(radiance.width, radiance.height, radiance.channels, Image::Uninitialized{});
  for (size_t i = 0; i < radiance.pixels.size(); ++i)
    out.pixels[i] = quantizer.value(exposure(radiance.pixels[i]));
  return out;
}

}  // namespace

std::shared_ptr<const View> make_view(std::shared_ptr<const Scene> scene,
                                      std::shared_ptr<const RayTracer> tracer, RenderResult render,
                                      int bits, bool lab) {
  auto view = std::make_shared<View>();
  view->encoding = scene->display.encoding;
  view->bits = bits;
  view->display =
      quantized_display(render.radiance, scene->display.exposure(), view->encoding, bits);
  if (lab) view->lab = display_to_lab(view->display, view->encoding, bits, &view->lightness);
  view->depth = render.gbuffer.depth;
  view->render = std::move(render);
  view->scene = std::move(scene);
  view->tracer = std::move(tracer);
  return view;
}

std::shared_ptr<const View> make_image_view(Image display, std::vector<float> depth,
                                            const DisplayEncoding& encoding, int bits, bool round) {
  auto view = std::make_shared<View>();
  view->encoding = encoding;
  view->bits = bits;
  view->display = std::move(display);
  if (round) quantize_in_place(view->display, bits);
  view->lab = display_to_lab(view->display, encoding, bits, &view->lightness);
  view->depth = std::move(depth);
  return view;
}

}  // namespace countershade
