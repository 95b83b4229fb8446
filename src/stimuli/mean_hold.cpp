#include "stimuli/mean_hold.h"

#include <algorithm>
#include <cmath>

#include "enhance/lightness.h"

namespace countershade {

double mean_lightness(const Image& display, const DisplayEncoding& encoding, int bits) {
  const LabPixels lab = display_to_lab(display, encoding, bits);
  double sum = 0;
  for (const Lab& p : lab) sum += p.L;
  return lab.empty() ? 0.0 : sum / double(lab.size());
}

namespace {

bool is_object(const View& view, size_t i) {
  return view.depth.empty() || (std::isfinite(view.depth[i]) && view.depth[i] > 0);
}

// The change "δ L* on every object pixel": a scaled change of amount 1 there, composed at λ = δ.
LightnessChange uniform_offset(const View& view) {
  LightnessChange change;
  change.kind = LightnessChange::Kind::scaled;
  change.amount.resize(size_t(view.width()) * size_t(view.height()));
  for (size_t i = 0; i < change.amount.size(); ++i) change.amount[i] = is_object(view, i) ? 1.0 : 0.0;
  return change;
}

}  // namespace

HeldMean hold_mean_lightness(const View& view, const Image& display, double tolerance) {
  HeldMean held{display, 0.0, 0};
  if (display.pixels == view.display.pixels) return held;
  const double target = mean_lightness(view.display, view.encoding, view.bits);
  const auto stimulus = make_image_view(display, view.depth, view.encoding, view.bits);
  const LightnessChange change = uniform_offset(*stimulus);
  auto error_at = [&](double offset, Composed* out) {
    Composed c = compose_lightness(*stimulus, change, offset, 1);
    const double error = mean_lightness(c.display, view.encoding, view.bits) - target;
    if (out) *out = std::move(c);
    return error;
  };
  // The mean rises monotonically with δ and nearly linearly (by the object's share of the image
  // per unit of δ, less where pixels clip), so a secant search from δ = 0 finds it in a few
  // compositions; a step that leaves the bracket of known signs bisects it instead.
  const double share = double(std::count(change.amount.begin(), change.amount.end(), 1.0)) / double(change.amount.size());
  Composed best{display, 0};
  double best_offset = 0, best_error = mean_lightness(display, view.encoding, view.bits) - target;
  if (share == 0) return held;
  double lo = -100, hi = 100, x0 = 0, f0 = best_error, x1 = -best_error / share;
  (f0 < 0 ? lo : hi) = 0.0;
  for (int step = 0; step < 30 && std::abs(best_error) > tolerance && hi - lo > 1e-3; ++step) {
    x1 = std::clamp(x1, lo, hi);
    Composed c;
    const double f1 = error_at(x1, &c);
    if (std::abs(f1) < std::abs(best_error)) best_error = f1, best_offset = x1, best = std::move(c);
    (f1 < 0 ? lo : hi) = x1;
    // Quantisation makes the mean a step function of δ (a uniform face moves by whole codes at
    // once): a flat step gives no slope, and the bracket is halved instead.
    double next = f1 != f0 ? x1 - f1 * (x1 - x0) / (f1 - f0) : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    x0 = x1, f0 = f1, x1 = next;
  }
  held.display = std::move(best.display);
  held.offset = best_offset;
  held.clipped_pixels = best.clipped_pixels;
  return held;
}

}  // namespace countershade
