#include "stimuli/mean_hold.h"

#include <algorithm>
#include <cmath>

#include "enhance/lightness.h"

namespace countershade {

namespace {

bool is_object(const View& view, size_t i) {
  return view.depth.empty() || (std::isfinite(view.depth[i]) && view.depth[i] > 0);
}

// The change "δ L* on every object pixel": a scaled change of amount 1 there, composed at λ = δ.
LightnessChange uniform_offset(const View& view) {
  LightnessChange change;
  change.kind = LightnessChange::Kind::scaled;
  change.amount.resize(size_t(view.width()) * size_t(view.height()));
  for (size_t i = 0; i < change.amount.size(); ++i)
    change.amount[i] = is_object(view, i) ? 1.0 : 0.0;
  return change;
}

}  // namespace

namespace {

// An offset tried: the stimulus it gives and how far that stimulus's mean is from the target.
struct Tried {
  double offset = 0, error = 0;
  Composed composed;
};

// The mean rises monotonically with δ and nearly linearly (by the object's share of the image per
// unit of δ, less where pixels clip), so a secant search from δ = 0 finds it in a few
// compositions; a step that leaves the bracket of known signs bisects it instead. The pixels a
// method leaves as they were hold exact codes, so they all reach their next code at about the
// same δ (half a code's L*, near 0.19 for mid greys): there the mean jumps by up to a tenth of an
// L*, and only the small differences between neighbouring codes' thresholds (under 1e-3 of δ)
// reach the values in between, which is why the bracket narrows that far.
Tried closest_offset(const std::function<double(double, Composed*)>& error_at, Tried best,
                     double share, double tolerance) {
  double lo = -100, hi = 100, x0 = 0, f0 = best.error, x1 = -best.error / share;
  (f0 < 0 ? lo : hi) = 0.0;
  for (int step = 0; step < 60 && std::abs(best.error) > tolerance && hi - lo > 1e-7; ++step) {
    x1 = std::clamp(x1, lo, hi);
    Composed c;
    const double f1 = error_at(x1, &c);
    if (std::abs(f1) < std::abs(best.error)) best = {x1, f1, std::move(c)};
    (f1 < 0 ? lo : hi) = x1;
    // Quantisation makes the mean a step function of δ (pixels move by whole codes): a flat step
    // gives no slope, and the bracket is halved instead.
    double next = f1 != f0 ? x1 - f1 * (x1 - x0) / (f1 - f0) : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    x0 = x1, f0 = f1, x1 = next;
  }
  return best;
}

}  // namespace

HeldMean hold_mean_lightness(const View& view, const Composed& stimulus, double tolerance,
                             const OffsetComposer& recompose) {
  if (stimulus.display.pixels == view.display.pixels)
    return {stimulus.display, 0.0, stimulus.clipped_pixels};
  const double target = mean_display_lightness(view.display, view.encoding, view.bits);
  const LightnessChange change = uniform_offset(view);
  const double share = double(std::count(change.amount.begin(), change.amount.end(), 1.0)) /
                       double(change.amount.size());
  if (share == 0) return {stimulus.display, 0.0, stimulus.clipped_pixels};
  std::shared_ptr<const View>
      own;  // the stimulus as a view, made only if the method cannot compose offsets
  auto error_at = [&](double offset, Composed* out) {
    std::optional<Composed> c = recompose ? recompose(offset, change.amount) : std::nullopt;
    if (!c) {  // the offset on the stimulus as its method composed it (unrounded, for RGB
               // operators)
      if (!own)
        own = make_image_view(stimulus.display, view.depth, view.encoding, view.bits, false);
      c = compose_lightness(*own, change, offset, 1);
      quantize_in_place(
          c->display,
          view.bits);  // the pixels the offset leaves keep the method's values until here
      c->clipped_pixels += stimulus.clipped_pixels;
    }
    const double error = mean_display_lightness(c->display, view.encoding, view.bits) - target;
    if (out) *out = std::move(*c);
    return error;
  };
  const double error = mean_display_lightness(stimulus.display, view.encoding, view.bits) - target;
  Tried best = closest_offset(error_at, {0.0, error, stimulus}, share, tolerance);
  return {std::move(best.composed.display), best.offset, best.composed.clipped_pixels};
}

HeldMean hold_mean_lightness(const View& view, const PreparedEnhancement& prepared, double lambda,
                             const Composed& stimulus) {
  return hold_mean_lightness(view, stimulus, 0.005,
                             [&](double offset, std::span<const double> where) {
                               return prepared.compose_offset(lambda, offset, where);
                             });
}

}  // namespace countershade
