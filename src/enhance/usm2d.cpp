#include "enhance/usm2d.h"

#include <cmath>

#include "core/error.h"
#include "core/gaussian.h"

namespace countershade {

void validate_image_width(const std::string& method, const MethodOptions& o) {
  int given = int(o.kernel_percent.has_value()) + int(o.sigma_px.has_value()) + int(o.sigma_percent.has_value());
  if (given != 1) throw InputError(method + ": give exactly one of --kernel, --sigma-px or --sigma-percent");
  if (o.kernel_percent && !(*o.kernel_percent > 0 && *o.kernel_percent <= 50))
    throw InputError("--kernel: must be more than 0% and at most 50% of the image diagonal");
  if (o.sigma_percent && !(*o.sigma_percent > 0 && *o.sigma_percent <= 12.5))
    throw InputError("--sigma-percent: must be more than 0% and at most 12.5% of the image diagonal");
  if (o.sigma_px && !(*o.sigma_px > 0 && std::isfinite(*o.sigma_px)))
    throw InputError("--sigma-px: must be a positive number of pixels");
}

void Usm2dMethod::validate(const MethodOptions& options) const { validate_image_width("usm2d", options); }

namespace {

class Usm2dPrepared final : public PreparedEnhancement {
 public:
  Usm2dPrepared(const View& view, std::vector<float> lightness, std::vector<float> blurred, double sigma)
      : view_(view), lightness_(std::move(lightness)), blurred_(std::move(blurred)), sigma_(sigma) {}

  Composed compose(double lambda) const override {
    std::vector<double> delta(lightness_.size());
    for (size_t i = 0; i < delta.size(); ++i) delta[i] = lambda * (double(lightness_[i]) - double(blurred_[i]));
    return compose_lightness(view_.display, view_.lab, delta, view_.encoding);
  }
  nlohmann::json parameters() const override { return {{"sigma_px", sigma_}}; }
  std::vector<std::pair<std::string, Image>> auxiliary() const override {
    Image blurred(view_.width(), view_.height(), 1);
    blurred.pixels.assign(blurred_.begin(), blurred_.end());
    return {{"lightness_blurred", blurred}};
  }

 private:
  const View& view_;
  std::vector<float> lightness_, blurred_;
  double sigma_;
};

}  // namespace

std::unique_ptr<PreparedEnhancement> Usm2dMethod::prepare(const View& view, const MethodOptions& options) const {
  validate(options);
  double sigma = image_sigma_px(options, view.width(), view.height());
  std::vector<float> lightness(view.lab.size()), blurred(view.lab.size());
  for (size_t i = 0; i < lightness.size(); ++i) lightness[i] = float(view.lab[i].L);
  gaussian_blur(lightness.data(), blurred.data(), view.width(), view.height(), sigma);
  return std::make_unique<Usm2dPrepared>(view, std::move(lightness), std::move(blurred), sigma);
}

}  // namespace countershade
