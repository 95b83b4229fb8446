#pragma once
// The width σ of the image-space methods (usm2d, depth-usm), given in exactly one of three ways:
// a kernel size K as % of the image diagonal (σ = K/4, the depth-buffer paper's convention), σ in
// pixels, or σ as % of the image diagonal.

#include <optional>
#include <string>
#include <vector>

#include "core/parameters.h"
#include "enhance/method.h"

namespace countershade {

struct ImageWidth {
  std::optional<double> kernel_percent, sigma_px, sigma_percent;
  // σ in pixels for an image of this size.
  double sigma_px_for(int width, int height) const;
};

// Reads kernel_percent (or its text form "kernel": "5%"), sigma_px and sigma_percent.
ImageWidth read_image_width(const ParameterBag& bag);
// Checks that exactly one was given, in range. Call after bag.finish(), so that an unknown key
// is reported first.
void check_image_width(const ImageWidth& width, const ParameterBag& bag, const std::string& method);
std::vector<WidthAxis> image_width_axes();
std::vector<ParameterDoc> image_width_docs();

}  // namespace countershade
