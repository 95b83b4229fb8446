#include "enhance/image_width.h"

#include <cmath>
#include <cstdlib>

#include "core/error.h"

namespace countershade {

double ImageWidth::sigma_px_for(int width, int height) const {
  const double diagonal = std::hypot(double(width), double(height));
  if (sigma_px) return *sigma_px;
  if (sigma_percent) return *sigma_percent / 100.0 * diagonal;
  if (kernel_percent) return *kernel_percent / 100.0 * diagonal / 4.0;
  return 0.0;
}

namespace {

// "5%" or "5" -> 5.
std::optional<double> kernel_text(const ParameterBag& bag) {
  auto text = bag.text("kernel");
  if (!text) return std::nullopt;
  std::string t = *text;
  if (!t.empty() && t.back() == '%') t.pop_back();
  char* end = nullptr;
  double v = std::strtod(t.c_str(), &end);
  if (t.empty() || end != t.c_str() + t.size() || !std::isfinite(v))
    bag.fail("kernel", "expected a percentage of the image diagonal like 5%, got '" + *text + "'");
  return v;
}

}  // namespace

ImageWidth read_image_width(const ParameterBag& bag) {
  ImageWidth w;
  w.kernel_percent = bag.optional_number("kernel_percent");
  if (auto k = kernel_text(bag)) {
    if (w.kernel_percent) bag.fail("kernel", "give the kernel once (kernel or kernel_percent)");
    w.kernel_percent = k;
  }
  w.sigma_px = bag.optional_number("sigma_px");
  w.sigma_percent = bag.optional_number("sigma_percent");
  return w;
}

void check_image_width(const ImageWidth& w, const ParameterBag& bag, const std::string& method) {
  const int given = int(w.kernel_percent.has_value()) + int(w.sigma_px.has_value()) +
                    int(w.sigma_percent.has_value());
  if (given != 1)
    throw_input_error(method, "give exactly one width: " + bag.where("kernel") + ", " +
                                  bag.where("sigma_px") + " or " + bag.where("sigma_percent"));
  const std::string kernel_key = bag.has("kernel") ? "kernel" : "kernel_percent";
  if (w.kernel_percent && !(*w.kernel_percent > 0 && *w.kernel_percent <= 50))
    bag.fail(kernel_key, "must be more than 0% and at most 50% of the image diagonal");
  if (w.sigma_percent && !(*w.sigma_percent > 0 && *w.sigma_percent <= 12.5))
    bag.fail("sigma_percent", "must be more than 0% and at most 12.5% of the image diagonal");
  if (w.sigma_px && !(*w.sigma_px > 0)) bag.fail("sigma_px", "must be a positive number of pixels");
}

std::vector<WidthAxis> image_width_axes() {
  return {
      {"kernel_percent", "% of the image diagonal",
       "kernel size K; σ = K/4 (the kernel spans ±2σ)"},
      {"sigma_px", "px", "Gaussian σ in pixels"},
      {"sigma_percent", "% of the image diagonal", "Gaussian σ as a share of the image diagonal"}};
}

std::vector<ParameterDoc> image_width_docs() {
  return {{"kernel", "",
           "kernel size K as % of the image diagonal, e.g. 5% (σ = K/4); kernel_percent in "
           "experiments"},
          {"sigma_px", "", "Gaussian σ in pixels"},
          {"sigma_percent", "", "Gaussian σ as % of the image diagonal"}};
}

}  // namespace countershade
