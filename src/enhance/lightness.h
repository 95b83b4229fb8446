#pragma once
// The one lightness-only composition every lightness method uses (docs/methods, "Colour"):
// L' = clamp(L + Δ, 0, 100) with a*, b* scaled by L'/L (hue and saturation kept), back to
// display code values, clipped per channel, with a count of clipped pixels. A method describes
// its Δ per pixel as a LightnessChange once per σ; composing a λ is then one pass.

#include <cstddef>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "core/color.h"
#include "core/display.h"
#include "core/image.h"
#include "enhance/display_lab.h"
#include "enhance/method.h"

namespace countershade {

// The L* plane of the view's own (plain) image.
std::vector<float> view_lightness(const View& view);

// The L* plane of the view's image before its quantisation to code values: from the rendered
// radiance (exposed and clamped as for display) where the view has it, else view_lightness.
// Image-space filters take their detail from this plane, so that a gain multiplies the image's
// detail and not the steps of its 8-bit quantisation (which it would turn into contour lines).
// Made once per view (the view keeps it), so every σ and method of a view shares it.
std::span<const float> view_signal_lightness(const View& view);

// Δ of every pixel for strength λ, in one of three forms (compose_lightness evaluates them).
struct LightnessChange {
  enum class Kind {
    scaled,   // Δ = (λ·factor·gain)·amount
    blended,  // Δ = clamp(λ·weight, 0, 1)·amount
    // Δ = (λ·factor)·(S − smooth), S the view's signal lightness (view_signal_lightness): an
    // image's detail, read from its two planes rather than stored as a third (16 MB at
    // 1920×1080). LightnessPrepared lists `smooth` among its auxiliary images.
    detail,
  };
  Kind kind = Kind::scaled;
  double factor = 1.0;  // scaled, detail: a constant factor (e.g. ΔL* per unit of λ)
  PixelDoubles amount;  // scaled, blended: per pixel; not zero-filled on resize, since every method
                        // writes it all
  std::vector<double> gain;   // scaled: an optional per-pixel gain (empty: 1)
  std::vector<float> weight;  // blended: per pixel
  PixelVector smooth;         // detail: per pixel
};

// A uniform L* offset on some pixels, composed with a change (PreparedEnhancement::compose_offset).
struct LightnessOffset {
  double offset = 0;
  std::span<const double> where;  // per pixel: 1 where the offset applies, 0 elsewhere
};

// Applies the change at strength λ (and the offset, if any) to the view's stimulus. Pixels whose
// Δ is 0 keep their code values exactly, so λ = 0 reproduces the view bit for bit.
Composed compose_lightness(const View& view, const LightnessChange& change, double lambda,
                           int threads = 0, const LightnessOffset* offset = nullptr);

// The sampling noise of the stimulus of strength λ (PreparedEnhancement::noise).
using NoiseFunction = std::function<NoiseModel(double lambda)>;

// The noise of L + λ·c from the render's estimate of the context's change (none: the view's).
NoiseFunction plain_noise(const PrepareContext& context);

// The prepared state of every lightness method: the view, its change, and what to record.
class LightnessPrepared final : public PreparedEnhancement {
 public:
  LightnessPrepared(std::shared_ptr<const View> view, LightnessChange change,
                    nlohmann::json parameters,
                    std::vector<std::pair<std::string, Image>> auxiliary = {}, int threads = 0,
                    NoiseFunction noise = {})
      : view_(std::move(view)),
        change_(std::move(change)),
        parameters_(std::move(parameters)),
        auxiliary_(std::move(auxiliary)),
        threads_(threads),
        noise_(std::move(noise)) {}

  Composed compose(double lambda) const override {
    return compose_lightness(*view_, change_, lambda, threads_);
  }
  std::optional<Composed> compose_offset(double lambda, double offset,
                                         std::span<const double> where) const override {
    const LightnessOffset uniform{offset, where};
    return compose_lightness(*view_, change_, lambda, threads_, &uniform);
  }
  nlohmann::json parameters() const override { return parameters_; }
  std::vector<std::pair<std::string, Image>> auxiliary() const override;
  NoiseModel noise(double lambda) const override { return noise_ ? noise_(lambda) : NoiseModel{}; }
  // The mask set by set_mask; else, for a `detail` change, its smooth plane; else none.
  std::vector<float> mask() const override;
  // The method's low-pass signal M (PreparedEnhancement::mask), made when asked for.
  void set_mask(std::function<std::vector<float>()> mask) { mask_ = std::move(mask); }
  const LightnessChange& change() const { return change_; }

 private:
  std::shared_ptr<const View> view_;
  LightnessChange change_;
  nlohmann::json parameters_;
  std::vector<std::pair<std::string, Image>> auxiliary_;
  int threads_;
  NoiseFunction noise_;
  std::function<std::vector<float>()> mask_;
};

}  // namespace countershade
