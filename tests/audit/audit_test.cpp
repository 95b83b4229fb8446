// The stimulus audit: its measures on hand-made images, and broken sets it must catch.

#include "audit/audit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <tuple>

#include "../adjust/tiny_set.h"
#include "core/color.h"
#include "core/display.h"
#include "core/error.h"
#include "core/image.h"
#include "core/sha256.h"
#include "enhance/lightness.h"
#include "formats/manifest.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

// L* of an sRGB grey code value, from the definitions.
double grey_lightness(int code) { return cielab_lightness(srgb_decode(code / 255.0)); }

Image grey_image(int width, int height, const std::vector<int>& codes) {
  Image image(width, height, 3);
  for (size_t p = 0; p < codes.size(); ++p)
    for (int c = 0; c < 3; ++c) image.pixels[3 * p + size_t(c)] = float(codes[p]) / 255.0f;
  return image;
}

ManifestEntry entry_for(const fs::path& set, const std::string& file, double lambda,
                        bool reference) {
  ManifestEntry e;
  e.file = file;
  e.scene = "grey";
  e.method = reference ? kReferenceMethod : "usm2d";
  if (!reference) {
    e.label = "usm2d";
    e.sigma = 2.0;
  }
  e.lambda = lambda;
  e.width = 4;
  e.height = 2;
  e.size = fs::file_size(set / file);
  e.sha256 = sha256_file(set / file);
  return e;
}

// A reference of one grey, a λ = 0 copy, and a stimulus with half its pixels lighter.
TEST(Audit, MeasuresMatchHandComputedImages) {
  testing::TempDir dir;
  const fs::path set = dir / "set";
  fs::create_directories(set / "grey/usm2d");
  write_image(set / "grey/reference.png", grey_image(4, 2, std::vector<int>(8, 100)));
  write_image(set / "grey/usm2d/lambda-0.png", grey_image(4, 2, std::vector<int>(8, 100)));
  write_image(set / "grey/usm2d/lambda-1.png",
              grey_image(4, 2, {100, 200, 100, 200, 100, 200, 100, 255}));
  Manifest m;
  m.experiment_name = "hand";
  m.lambda_grid = {0.0, 1.0, 1.0, 2};
  m.stimuli = {entry_for(set, "grey/reference.png", 0, true),
               entry_for(set, "grey/usm2d/lambda-0.png", 0, false),
               entry_for(set, "grey/usm2d/lambda-1.png", 1, false)};
  write_manifest(set / "manifest.json", m);
  const AuditReport r = audit_stimulus_set(set / "manifest.json");
  ASSERT_EQ(r.stimuli.size(), 3u);
  const double L100 = grey_lightness(100), L200 = grey_lightness(200), L255 = grey_lightness(255);
  // L* to 1e-5: the audit decodes with the generator's fast conversion (docs/performance.md).
  EXPECT_NEAR(r.stimuli[0].mean_lightness, L100, 1e-5);
  EXPECT_NEAR(r.stimuli[0].rms_contrast, 0.0, 1e-9);
  const StimulusAudit& s = r.stimuli[2];
  const double mean = (4 * L100 + 3 * L200 + L255) / 8;
  EXPECT_NEAR(s.mean_lightness, mean, 1e-5);
  const double variance =
      (4 * std::pow(L100 - mean, 2) + 3 * std::pow(L200 - mean, 2) + std::pow(L255 - mean, 2)) / 8;
  EXPECT_NEAR(s.rms_contrast, std::sqrt(variance), 1e-5);
  EXPECT_DOUBLE_EQ(s.changed_fraction, 0.5);
  EXPECT_DOUBLE_EQ(s.clipped_fraction, 0.125);  // the one pixel driven to 255
  // Greys differ in lightness only: ΔE00 = |ΔL*| / S_L at the mean lightness.
  auto grey_difference = [](double a, double b) {
    const double m = 0.5 * (a + b), d = (m - 50) * (m - 50);
    return std::abs(b - a) / (1 + 0.015 * d / std::sqrt(20 + d));
  };
  EXPECT_NEAR(s.delta_e_mean, (3 * grey_difference(L100, L200) + grey_difference(L100, L255)) / 8,
              1e-5);
  // The 99th percentile is the value at ⌊0.99·(n − 1)⌋ = 6 of the 8 sorted differences.
  EXPECT_NEAR(s.delta_e_p99, grey_difference(L100, L200), 1e-4);
  // λ = 0 equals the reference; λ = 1 drifts by far more than 1 L* and clips 12.5 %.
  for (const auto& c : r.checks) {
    if (c.check == "lambda 0 equals reference") {
      EXPECT_TRUE(c.passed) << c.detail;
    }
    if (c.check == "mean L* drift" || c.check == "clipped pixels") {
      EXPECT_FALSE(c.passed) << c.detail;
    }
  }
}

TEST(Audit, LimitsComeFromTheExperimentAndTheScreenMustHoldTwoImages) {
  const nlohmann::json block = {{"max_drift", 0.5}, {"screen", {{"width", 1000}, {"height", 800}}}};
  const AuditLimits limits = read_audit_limits(JsonObject(block, "experiment.json", "audit"));
  EXPECT_EQ(limits.max_drift, 0.5);
  EXPECT_EQ(limits.max_clipped, 0.01);
  EXPECT_EQ(limits.screen_width, 1000);
  EXPECT_THROW(read_audit_limits(JsonObject({{"max_drfit", 1}}, "experiment.json", "audit")),
               InputError);
  EXPECT_THROW(read_audit_limits(JsonObject({{"max_clipped", 2}}, "experiment.json", "audit")),
               InputError);
  Manifest m;
  ManifestEntry e;
  e.width = 512;
  e.height = 384;
  m.stimuli = {e};
  AuditReport r;
  r.limits = limits;
  add_audit_checks(r, m);
  ASSERT_EQ(r.checks.size(), 1u);
  EXPECT_FALSE(r.checks[0].passed) << "2 × 512 + 48 > 1000";
  r.checks.clear();
  r.limits.screen_width = 1072;
  add_audit_checks(r, m);
  EXPECT_TRUE(r.checks[0].passed) << r.checks[0].detail;
}

std::optional<AuditCheck> check_named(const AuditReport& r, const std::string& name) {
  for (const auto& c : r.checks)
    if (c.check == name) return c;
  return std::nullopt;
}

// A failed drift or clipping check names the largest value and the smallest λ past the limit:
// whether the λ range around the first visible difference is affected.
TEST(Audit, AFailedCheckSaysFromWhichLambdaTheLimitIsPassed) {
  AuditReport r;
  const double drifts[] = {0, 0.4, -1.2, 0.9, 2.5}, clipped[] = {0, 0, 0.004, 0.02, 0.03};
  for (int k = 0; k < 5; ++k) {
    StimulusAudit s;
    s.scene = "scan";
    s.condition = "usm3d sigma 0.12";
    s.lambda = 0.5 * k;
    s.drift = drifts[k];
    s.clipped_fraction = clipped[k];
    r.stimuli.push_back(s);
  }
  std::swap(r.stimuli[1], r.stimuli[4]);  // the checks must not depend on the manifest's order
  add_audit_checks(r, Manifest{});
  const auto drift = check_named(r, "mean L* drift"), clipping = check_named(r, "clipped pixels");
  ASSERT_TRUE(drift && clipping);
  EXPECT_FALSE(drift->passed);
  EXPECT_EQ(drift->detail, "+2.5 L* at lambda 2 (limit 1; past it from lambda 1)");
  EXPECT_FALSE(clipping->passed);
  EXPECT_EQ(clipping->detail, "3 % at lambda 2 (limit 1 %; past it from lambda 1.5)");
  // The summary line counts the failures of each kind.
  EXPECT_EQ(r.summary().rfind(
                "5 images, 5 checks, 2 failed (1 mean L* drift, 1 clipped pixels): scan usm3d", 0),
            0u)
      << r.summary();
  r.limits.max_drift = 3;
  r.checks.clear();
  add_audit_checks(r, Manifest{});
  EXPECT_EQ(check_named(r, "mean L* drift")->detail,
            "+2.5 L* at lambda 2 (limit 3)");  // passed: no clause
}

// One condition's stimuli from (λ, frame, checksum, share of pixels changed against the reference).
AuditReport condition_of_images(
    const std::vector<std::tuple<double, int, std::string, double>>& images) {
  AuditReport r;
  for (const auto& [lambda, frame, sha, changed] : images) {
    StimulusAudit s;
    s.scene = "ball";
    s.condition = "lla sigma 0.1";
    s.lambda = lambda;
    s.frame = frame;
    s.sha256 = sha;
    s.changed_fraction = changed;
    r.stimuli.push_back(s);
  }
  add_audit_checks(r, Manifest{});
  return r;
}

TEST(Audit, AnEnhancementThatStopsChangingAlongTheGridIsFlagged) {
  const std::string steps = "every lambda step changes the image";
  // Saturation from λ = 1 on (the manifest's order does not matter).
  auto saturated = check_named(condition_of_images({{2, -1, "c", 0.3},
                                                    {0, -1, "r", 0},
                                                    {0.5, -1, "b", 0.2},
                                                    {1, -1, "c", 0.3},
                                                    {1.5, -1, "c", 0.3}}),
                               steps);
  ASSERT_TRUE(saturated);
  EXPECT_FALSE(saturated->passed);
  EXPECT_EQ(saturated->detail,
            "the same image from lambda 1 to 2 (3 grid values): the enhancement stops changing");
  // A control scene: every image is the reference's, nothing is enhanced, nothing to flag.
  EXPECT_TRUE(
      check_named(condition_of_images({{0, -1, "r", 0}, {1, -1, "r", 0}, {2, -1, "r", 0}}), steps)
          ->passed);
  // Clamped at 0 below: negative λ repeat the reference while positive ones enhance.
  auto below =
      check_named(condition_of_images(
                      {{-1, -1, "r", 0}, {-0.5, -1, "r", 0}, {0, -1, "r", 0}, {0.5, -1, "b", 0.2}}),
                  steps);
  EXPECT_FALSE(below->passed);
  EXPECT_EQ(below->detail,
            "the same image from lambda -1 to 0 (3 grid values): the enhancement stops changing");
  // A sequence: frames are compared with the same frame at the next λ, not with each other.
  auto frames =
      check_named(condition_of_images(
                      {{1, 0, "f0", 0.2}, {1, 1, "f0", 0.2}, {2, 0, "g0", 0.3}, {2, 1, "f0", 0.2}}),
                  steps);
  EXPECT_FALSE(frames->passed);
  EXPECT_EQ(
      frames->detail,
      "the same image from lambda 1 to 2 (2 grid values, frame 1): the enhancement stops changing");
  EXPECT_TRUE(
      check_named(condition_of_images(
                      {{1, 0, "f0", 0.2}, {1, 1, "f0", 0.2}, {2, 0, "g0", 0.3}, {2, 1, "g1", 0.3}}),
                  steps)
          ->passed);
}

// The failing checks of one kind, as "scene/condition".
std::set<std::string> failing(const AuditReport& r, const std::string& check) {
  std::set<std::string> out;
  for (const auto& c : r.checks)
    if (c.check == check && !c.passed) out.insert(c.scene + "/" + c.condition);
  return out;
}

// Replaces a set's image and records its new checksum in the manifest.
void replace_image(const fs::path& manifest_path, const std::string& file, const Image& image) {
  const fs::path set = manifest_path.parent_path();
  write_image(set / file, image);
  Manifest m = read_manifest(manifest_path);
  for (auto& e : m.stimuli)
    if (e.file == file) {
      e.size = fs::file_size(set / file);
      e.sha256 = sha256_file(set / file);
    }
  write_manifest(manifest_path, m);
}

Image brightened(const Image& in, double lightness) {
  Image out = in;
  const DisplayEncoding srgb = DisplayEncoding::srgb();
  for (size_t p = 0; p < in.pixels.size() / 3; ++p) {
    const Lab lab = display_pixel_to_lab(&in.pixels[3 * p], srgb);
    const glm::dvec3 rgb = lab_to_linear_rgb(with_lightness(lab, lab.L + lightness));
    for (int c = 0; c < 3; ++c)
      out.pixels[3 * p + size_t(c)] =
          float(quantize(float(srgb_encode(std::clamp(rgb[c], 0.0, 1.0))), 8)) / 255.0f;
  }
  return out;
}

std::string condition_of(const fs::path& manifest_path, const std::string& file) {
  for (const auto& e : read_manifest(manifest_path).stimuli)
    if (e.file == file)
      return e.scene + "/" + e.condition_method() + " sigma " + format_value(*e.sigma);
  return "";
}

TEST(Audit, ABrokenSetIsCaught) {
  testing::TempDir dir;
  const fs::path manifest = testing::make_tiny_set(dir);
  const AuditReport clean = audit_stimulus_set(manifest);
  EXPECT_TRUE(failing(clean, "lambda 0 equals reference").empty());
  const auto drift_before = failing(clean, "mean L* drift");
  // A λ > 0 image brightened by 3 L*, its checksum updated: exactly its condition starts to drift.
  const std::string bright = "front/usm3d/sigma-0.03/lambda-0.8.png";
  const std::string bright_condition = condition_of(manifest, bright);
  ASSERT_FALSE(bright_condition.empty());
  ASSERT_EQ(drift_before.count(bright_condition), 0u);
  replace_image(manifest, bright, brightened(read_image(manifest.parent_path() / bright), 3.0));
  // A λ = 0 image re-encoded with one pixel one code lighter: flagged.
  const std::string zero = "small/usm3d/sigma-0.08/lambda-0.png";
  Image changed = read_image(manifest.parent_path() / zero);
  changed.pixels[0] = std::min(1.0f, changed.pixels[0] + 1.0f / 255.0f);
  replace_image(manifest, zero, changed);
  const AuditReport broken = audit_stimulus_set(manifest);
  auto drift_after = failing(broken, "mean L* drift");
  for (const auto& c : drift_before) drift_after.erase(c);
  EXPECT_EQ(drift_after, std::set<std::string>{bright_condition});
  EXPECT_EQ(failing(broken, "lambda 0 equals reference"),
            std::set<std::string>{condition_of(manifest, zero)});
  // The CLI: --strict exits 1 on failed checks; without it the audit succeeds.
  EXPECT_EQ(
      testing::run_cli("audit " + manifest.string() + " -o " + (dir / "report").string()).exit_code,
      0);
  EXPECT_EQ(testing::run_cli("audit " + manifest.string() + " -o " + (dir / "report").string() +
                             " --strict")
                .exit_code,
            1);
  EXPECT_TRUE(fs::exists(dir / "report/report.html"));
  // An image changed without its manifest: refused before any measurement, exit 2.
  write_image(manifest.parent_path() / bright, read_image(manifest.parent_path() / zero));
  EXPECT_THROW(audit_stimulus_set(manifest), InputError);
  const auto refused =
      testing::run_cli("audit " + manifest.string() + " -o " + (dir / "report2").string());
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_EQ(testing::count_lines(refused.output), 1) << refused.output;
}

// Through a real set: exaggerated shading clamps its blend at λ = 1, so a grid up to 2 repeats
// one image; usm3d on the same scene keeps changing.
TEST(Audit, ARealSetWhoseMethodSaturatesIsFlagged) {
  testing::TempDir dir;
  const fs::path scene = testing::source_dir() / "experiments/drift/scenes/top.json";
  const fs::path experiment =
      testing::write_file(dir / "experiment.json", R"({
    "version": 1, "name": "saturation", "seed": 1,
    "lambda": {"min": 0, "max": 2, "step": 0.5},
    "scenes": [{"name": "ball", "file": ")" + scene.string() +
                                                       R"(", "width": 64, "height": 48, "spp": 4}],
    "methods": [{"method": "exaggerated-shading", "sigma": [0.2]}, {"method": "usm3d", "sigma": [0.6]}]
  })");
  ASSERT_EQ(testing::run_cli("stimuli " + experiment.string() + " -o " + (dir / "set").string())
                .exit_code,
            0);
  const AuditReport r = audit_stimulus_set(dir / "set/manifest.json");
  EXPECT_EQ(failing(r, "every lambda step changes the image"),
            std::set<std::string>{"ball/exaggerated-shading sigma 0.2"});
}

}  // namespace
}  // namespace countershade
