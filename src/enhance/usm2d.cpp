// 2D image unsharp masking of lightness (the classic baseline): C = L* − G_σ * L*, Δ = λ·C,
// composed lightness-only. σ in pixels, as % of the image diagonal, or from a kernel size K%
// (σ = K/4).

#include <cmath>

#include "core/gaussian.h"
#include "enhance/image_width.h"
#include "enhance/lightness.h"

namespace countershade {
namespace {

struct Usm2dParameters final : MethodParameters {
  ImageWidth width;
};

class Usm2dMethod final : public EnhancementMethod {
 public:
  std::string name() const override { return "usm2d"; }
  std::string summary() const override { return "2D unsharp masking of lightness in image space"; }
  MethodAxes axes() const override {
    return {"gain on the detail L* − G_σ*L*", image_width_axes()};
  }
  std::vector<ParameterDoc> parameter_docs() const override { return image_width_docs(); }

  std::shared_ptr<const MethodParameters> parse(const ParameterBag& bag) const override {
    auto p = std::make_shared<Usm2dParameters>();
    p->width = read_image_width(bag);
    if (bag.has("space"))
      bag.fail("space",
               "usm2d always works on lightness (CIELAB L*) and keeps hue and saturation; it has "
               "no space");
    bag.finish(name());
    check_image_width(p->width, bag, name());
    return p;
  }

  std::unique_ptr<PreparedEnhancement> prepare(const PrepareContext& context,
                                               const MethodParameters& parameters) const override {
    const View& view = *context.view;
    const double sigma =
        parameters_as<Usm2dParameters>(parameters).width.sigma_px_for(view.width(), view.height());
    const std::span<const float> lightness = view_signal_lightness(view);
    LightnessChange change;
    change.kind = LightnessChange::Kind::detail;  // Δ = λ·(L* − G_σ*L*)
    change.smooth.resize(lightness.size());
    gaussian_blur(lightness.data(), change.smooth.data(), view.width(), view.height(), sigma,
                  context.threads);
    return std::make_unique<LightnessPrepared>(
        context.view, std::move(change), nlohmann::json{{"sigma_px", sigma}},
        std::vector<std::pair<std::string, Image>>{}, context.threads, plain_noise(context));
  }

  // The detail L − G*L passes the pixel's noise (the blurred image's is negligible).
  std::shared_ptr<const ChangePerLambda> change_per_lambda(const MethodParameters&) const override {
    return std::make_shared<LightnessTimes>(1.0);
  }
};

}  // namespace

std::unique_ptr<const EnhancementMethod> make_usm2d_method() {
  return std::make_unique<Usm2dMethod>();
}

}  // namespace countershade
