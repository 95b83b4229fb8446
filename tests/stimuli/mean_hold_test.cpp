// Holding a stimulus's mean lightness at its reference's (an experiment's "hold_mean"): against
// L* computed here from the sRGB definitions, on a synthetic image and in a stimulus set whose
// audit then finds no drift.

#include "stimuli/mean_hold.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "audit/audit.h"
#include "core/image.h"
#include "enhance/lightness.h"
#include "enhance/method.h"
#include "set_test_util.h"
#include "stimuli/experiment.h"
#include "stimuli/stimulus_set.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

// CIELAB of an 8-bit sRGB code triple, from the standard's formulas (D65, Y of the white = 1);
// with `rounded` false, of the values as they are.
struct ReferenceLab {
  double L, a, b;
};
ReferenceLab reference_lab(const float* rgb, bool rounded = true) {
  double linear[3];
  for (int c = 0; c < 3; ++c) {
    const double v = rounded ? std::round(rgb[c] * 255.0) / 255.0 : double(rgb[c]);
    linear[c] = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
  }
  const double X = 0.4124564 * linear[0] + 0.3575761 * linear[1] + 0.1804375 * linear[2];
  const double Y = 0.2126729 * linear[0] + 0.7151522 * linear[1] + 0.0721750 * linear[2];
  const double Z = 0.0193339 * linear[0] + 0.1191920 * linear[1] + 0.9503041 * linear[2];
  auto f = [](double t) {
    return t > 216.0 / 24389.0 ? std::cbrt(t) : (24389.0 / 27.0 * t + 16.0) / 116.0;
  };
  const double fx = f(X / 0.95047), fy = f(Y), fz = f(Z / 1.08883);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

// The largest |L* − ideal| over the pixels where `ideal` is finite: how far rounding took each
// pixel from the L* it was meant to have. Rounded once, that is at most half a code's L*.
double largest_rounding_error(const Image& image, const std::vector<double>& ideal) {
  double largest = 0;
  for (size_t p = 0; p < ideal.size(); ++p)
    if (std::isfinite(ideal[p]))
      largest = std::max(largest, std::abs(reference_lab(&image.pixels[3 * p]).L - ideal[p]));
  return largest;
}

double reference_mean(const Image& image) {
  double sum = 0;
  for (size_t p = 0; p < image.pixels.size() / 3; ++p) sum += reference_lab(&image.pixels[3 * p]).L;
  return sum / double(image.pixels.size() / 3);
}

// A dark grey background (no depth) around an object of coloured stripes (depth 1).
std::shared_ptr<const View> striped_view() {
  const int w = 64, h = 48;
  Image display(w, h, 3);
  std::vector<float> depth(size_t(w) * h, INFINITY);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const bool object = x >= 12 && x < 52 && y >= 8 && y < 40;
      const float t = float((x / 4) % 5) / 4.0f;
      const float rgb[3] = {object ? 0.3f + 0.5f * t : 0.2f, object ? 0.35f + 0.2f * t : 0.2f,
                            object ? 0.5f - 0.3f * t : 0.2f};
      for (int c = 0; c < 3; ++c) display.pixels[3 * i + size_t(c)] = rgb[c];
      if (object) depth[i] = 1.0f;
    }
  return make_image_view(display, depth, DisplayEncoding::srgb(), 8);
}

TEST(MeanHold, AnEnhancedImageGetsItsReferencesMeanByOneOffsetOnItsObject) {
  const auto view = striped_view();
  // An "enhancement" that brightens the object: every channel of its pixels up by 20 codes (some
  // clip).
  Image enhanced = view->display;
  for (size_t p = 0; p < view->depth.size(); ++p)
    for (int c = 0; std::isfinite(view->depth[p]) && c < 3; ++c)
      enhanced.pixels[3 * p + size_t(c)] =
          std::min(1.0f, enhanced.pixels[3 * p + size_t(c)] + 20.0f / 255.0f);
  const double target = reference_mean(view->display);
  ASSERT_GT(std::abs(reference_mean(enhanced) - target), 0.3)
      << "the enhancement must move the mean to test anything";
  const HeldMean held = hold_mean_lightness(*view, {enhanced, 0});
  EXPECT_NEAR(reference_mean(held.display), target, 0.05);
  EXPECT_NEAR(mean_display_lightness(held.display, view->encoding, 8), target, 0.05);
  size_t object = 0;
  for (size_t p = 0; p < view->depth.size(); ++p) {
    const float* before = &enhanced.pixels[3 * p];
    const float* after = &held.display.pixels[3 * p];
    if (!std::isfinite(view->depth[p])) {  // the background keeps its codes
      for (int c = 0; c < 3; ++c) ASSERT_EQ(after[c], before[c]) << p;
      continue;
    }
    ++object;
    const ReferenceLab x = reference_lab(before), y = reference_lab(after);
    EXPECT_NEAR(y.L - x.L, held.offset, 0.6) << p;  // one offset, up to an 8-bit step
    const double hue_x = std::atan2(x.b, x.a), hue_y = std::atan2(y.b, y.a);
    if (std::hypot(x.a, x.b) > 10) {
      EXPECT_NEAR(std::remainder(hue_y - hue_x, 2 * std::numbers::pi), 0.0, 0.05) << p;
    }
  }
  EXPECT_GT(object, 1000u);
  // The reference itself, and a stimulus equal to it, stay as they are.
  const HeldMean same = hold_mean_lightness(*view, {view->display, 0});
  EXPECT_EQ(same.display.pixels, view->display.pixels);
  EXPECT_EQ(same.offset, 0.0);
}

// A flat face (one grey code over half the image) under a change that brightens it by a gentle
// ramp, 0 to 0.5 L* across it. Composed with the method's change before the one rounding, each
// pixel lands within half a code (0.19 L* at grey 128) of its reference L* plus ramp plus offset;
// an offset on the enhanced stimulus's codes rounds twice, and pixels land up to a whole code off.
TEST(MeanHold, TheOffsetComposedBeforeRoundingHoldsAFlatFaceFinerThanWholeCodes) {
  const int w = 64, h = 48;
  Image display(w, h, 3);
  std::vector<float> depth(size_t(w) * h, INFINITY);
  LightnessChange ramp;
  ramp.amount.assign(size_t(w) * h, 0.0);
  PixelDoubles where(size_t(w) * h, 0.0);
  for (size_t i = 0; i < depth.size(); ++i) {
    const bool object = int(i % w) < w / 2;
    for (int c = 0; c < 3; ++c)
      display.pixels[3 * i + size_t(c)] = object ? 128.0f / 255.0f : 40.0f / 255.0f;
    if (object)
      depth[i] = 1.0f, ramp.amount[i] = 0.5 * double(i % w) / double(w / 2 - 1), where[i] = 1.0;
  }
  const auto view = make_image_view(display, depth, DisplayEncoding::srgb(), 8);
  const LightnessPrepared prepared(view, ramp, nlohmann::json::object(), {}, 1);
  const double target = reference_mean(view->display);
  const double lambda = 1.0;
  const Composed enhanced = prepared.compose(lambda);
  const HeldMean on_codes = hold_mean_lightness(*view, enhanced);
  const HeldMean composed =
      hold_mean_lightness(*view, enhanced, 0.005, [&](double offset, std::span<const double> at) {
        return prepared.compose_offset(lambda, offset, at);
      });
  EXPECT_LT(std::abs(reference_mean(composed.display) - target), 0.01);
  std::vector<double> ideal_composed(depth.size(), NAN), ideal_on_codes(depth.size(), NAN);
  for (size_t i = 0; i < depth.size(); ++i) {
    if (where[i] != 1.0) continue;
    const double L = reference_lab(&view->display.pixels[3 * i]).L + lambda * ramp.amount[i];
    ideal_composed[i] = L + composed.offset;
    ideal_on_codes[i] = L + on_codes.offset;
  }
  const double half_code = 0.5 * 0.381;  // L* of codes 129 and 128, 53.966 and 53.585, halved
  EXPECT_LT(largest_rounding_error(composed.display, ideal_composed), half_code + 1e-3);
  EXPECT_GT(largest_rounding_error(on_codes.display, ideal_on_codes), half_code + 0.05);
  // The held stimulus is the method's own composition at the offset it records: rounded once.
  EXPECT_EQ(composed.display.pixels,
            prepared.compose_offset(lambda, composed.offset, where)->display.pixels);
}

// The same flat face under a method that composes in display RGB without rounding (as depth-usm's
// operators do): a ramp of 0 to 1.25 codes added to every channel. The offset goes onto its
// unrounded values, so the mean holds as finely as for a lightness method, and the result is
// rounded once.
TEST(MeanHold, AnRgbMethodsUnroundedStimulusTakesTheOffsetBeforeItsRounding) {
  const int w = 64, h = 48;
  Image display(w, h, 3);
  std::vector<float> depth(size_t(w) * h, INFINITY);
  PixelDoubles where(size_t(w) * h, 0.0);
  for (size_t i = 0; i < depth.size(); ++i) {
    const bool object = int(i % w) < w / 2;
    for (int c = 0; c < 3; ++c)
      display.pixels[3 * i + size_t(c)] = object ? 128.0f / 255.0f : 40.0f / 255.0f;
    if (object) depth[i] = 1.0f, where[i] = 1.0;
  }
  const auto view = make_image_view(display, depth, DisplayEncoding::srgb(), 8);
  Composed unrounded{view->display, 0};
  for (size_t i = 0; i < depth.size(); ++i)
    for (int c = 0; where[i] == 1.0 && c < 3; ++c)
      unrounded.display.pixels[3 * i + size_t(c)] +=
          float(1.25 * double(i % w) / double(w / 2 - 1) / 255.0);
  Composed rounded = unrounded;
  quantize_in_place(rounded.display, 8);
  const double target = reference_mean(view->display);
  const HeldMean on_codes = hold_mean_lightness(*view, rounded);
  const HeldMean composed = hold_mean_lightness(*view, unrounded);
  Image as_codes = composed.display;  // what the mean hold gives is rounded to codes
  quantize_in_place(as_codes, 8);
  EXPECT_EQ(as_codes.pixels, composed.display.pixels);
  EXPECT_LT(std::abs(reference_mean(composed.display) - target), 0.01);
  // Every face pixel is rounded once from its unrounded value plus the offset: within half a code
  // (under 0.2 L* here), where the offset on the rounded codes lands up to a whole code off.
  std::vector<double> ideal_composed(depth.size(), NAN), ideal_on_codes(depth.size(), NAN);
  for (size_t i = 0; i < depth.size(); ++i) {
    if (where[i] != 1.0) continue;
    const double L = reference_lab(&unrounded.display.pixels[3 * i], false).L;
    ideal_composed[i] = L + composed.offset;
    ideal_on_codes[i] = L + on_codes.offset;
  }
  EXPECT_LT(largest_rounding_error(composed.display, ideal_composed),
            0.2);  // half of 0.39 L*, codes 129 to 130
  EXPECT_GT(largest_rounding_error(on_codes.display, ideal_on_codes), 0.25);
}

// An object of two flat greys, codes 144 and 145 in alternate columns, that a method darkened in
// one small patch only: every other object pixel holds an exact code, so an offset moves each
// grey by a whole code at once, both at nearly the same δ (their thresholds differ by under 1e-3),
// and the mean jumps by a tenth of an L* at each. Held within 0.05 L* only by the offset between
// the two thresholds, which the search must narrow down to.
TEST(MeanHold, TheSearchFindsTheOffsetBetweenTwoFlatGreysThresholds) {
  const int w = 64, h = 48;
  Image display(w, h, 3);
  std::vector<float> depth(size_t(w) * h, INFINITY);
  for (size_t i = 0; i < depth.size(); ++i) {
    const bool object = int(i % w) < w / 2;
    const float code = object ? (i % 2 ? 145.0f : 144.0f) : 40.0f;
    for (int c = 0; c < 3; ++c) display.pixels[3 * i + size_t(c)] = code / 255.0f;
    if (object) depth[i] = 1.0f;
  }
  const auto view = make_image_view(display, depth, DisplayEncoding::srgb(), 8);
  Composed unrounded{view->display, 0};
  for (size_t i = 0; i < 12; ++i)  // a patch of 12 pixels darkened by 40.3 codes, unrounded
    for (int c = 0; c < 3; ++c)
      unrounded.display.pixels[3 * (i + 20 * size_t(w)) + size_t(c)] -= 40.3f / 255.0f;
  Composed rounded = unrounded;
  quantize_in_place(rounded.display, 8);
  const double target = reference_mean(view->display);
  ASSERT_LT(reference_mean(rounded.display) - target, -0.05)
      << "the patch must move the mean past the bound";
  const HeldMean held = hold_mean_lightness(*view, unrounded);
  EXPECT_LT(std::abs(reference_mean(held.display) - target), 0.05);
  // Between the thresholds: of the flat greys' channels, some have moved a code and some not.
  size_t moved = 0, flat = 0;
  for (size_t i = 0; i < depth.size(); ++i)
    for (int c = 0;
         std::isfinite(depth[i]) && !(i >= 20 * size_t(w) && i < 20 * size_t(w) + 12) && c < 3;
         ++c) {
      ++flat;
      moved += held.display.pixels[3 * i + size_t(c)] != view->display.pixels[3 * i + size_t(c)];
    }
  EXPECT_GT(moved, 0u);
  EXPECT_LT(moved, flat);
}

// A set of the lit cube under usm3d up to λ = 3 drifts without hold_mean and not with it; every
// stimulus records its offset, and λ = 0 is the reference byte for byte.
TEST(MeanHold, ASetWithHoldMeanPassesTheDriftCheck) {
  testing::TempDir dir;
  testing::write_file(dir / "cube.json", testing::kLitCubeScene);
  auto experiment = [&](bool hold) {
    return load_experiment(testing::write_file(dir / (hold ? "held.json" : "free.json"),
                                               std::string(R"({
      "version": 1, "name": "held", "seed": 5, "lambda": {"min": 0, "max": 3, "step": 1.5},
      "scenes": [{"name": "cube", "file": "cube.json", "width": 96, "height": 72}],
      "methods": [{"method": "usm3d", "sigma_fraction": [0.1]}], "audit": {"max_drift": 0.1})") +
                                                   (hold ? R"(, "hold_mean": true})" : "}")));
  };
  GenerateOptions options;
  for (bool hold : {false, true}) {
    const fs::path set = dir / (hold ? "held" : "free");
    generate_stimulus_set(experiment(hold), set, options);
    const AuditReport report = audit_stimulus_set(set / "manifest.json");
    const size_t failed = testing::failed_checks(report, "mean L* drift");
    EXPECT_EQ(failed, hold ? 0u : 1u) << (hold ? "held" : "free");
    if (!hold) continue;
    const Manifest manifest = read_manifest(set / "manifest.json");
    const Image reference = read_image(set / "cube/reference.png");
    for (const auto& entry : manifest.stimuli) {
      if (entry.method == kReferenceMethod) continue;
      ASSERT_TRUE(entry.extra.contains("mean_offset")) << entry.file;
      const Image image = read_image(set / entry.file);
      EXPECT_NEAR(reference_mean(image), reference_mean(reference), 0.05) << entry.file;
      if (entry.lambda == 0) {
        EXPECT_EQ(image.pixels, reference.pixels);
        EXPECT_EQ(entry.extra["mean_offset"].get<double>(), 0.0);
      }
    }
  }
}

}  // namespace
}  // namespace countershade
