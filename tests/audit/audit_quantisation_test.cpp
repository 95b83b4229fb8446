// The audit's quantisation column: on a 16-bit set, the share of each stimulus's change (L*
// against its reference) that 8 bits lose, against an independent computation from the 8-bit set
// made from the same render (the same experiment at "bits": 8), with sRGB decoded here by its
// formula; and the note naming the λ range where more than a quarter is lost.

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "audit/audit.h"
#include "core/image.h"
#include "stimuli/set_test_util.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

fs::path write_experiment(const testing::TempDir& dir, int bits) {
  std::string cube = testing::kLitCubeScene;
  cube.replace(cube.find("\"width\": 640, \"height\": 480"), 27, "\"width\": 160, \"height\": 120");
  testing::write_file(dir / "cube.json", cube);
  return testing::write_file(dir / ("experiment-" + std::to_string(bits) + ".json"), R"({
    "version": 1, "name": "quantisation", "seed": 4, "output": {"bits": )" + std::to_string(bits) +
                                                                                         R"(},
    "lambda": {"min": 0, "max": 1, "step": 0.05},
    "scenes": [{"name": "cube", "file": "cube.json"}],
    "methods": [{"method": "usm3d", "sigma": [0.1]}],
    "audit": {"max_drift": 5, "max_clipped": 0.5}})");
}

// L* per pixel of a PNG, sRGB decoded by its formula (D65, Rec. 709 primaries).
std::vector<double> lightness(const fs::path& file) {
  const Image image = read_image(file);
  std::vector<double> out(size_t(image.width) * image.height);
  for (size_t p = 0; p < out.size(); ++p) {
    double rgb[3];
    for (int c = 0; c < 3; ++c) {
      const double v = image.pixels[3 * p + c];
      rgb[c] = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    }
    const double y = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
    out[p] = y > 216.0 / 24389.0 ? 116.0 * std::cbrt(y) - 16.0 : y * 24389.0 / 27.0;
  }
  return out;
}

TEST(AuditQuantisation, TheLossMatchesThe8BitSetOfTheSameRender) {
  testing::TempDir dir;
  generate_stimulus_set(load_experiment(write_experiment(dir, 16)), dir / "16",
                        testing::with_jobs(2));
  generate_stimulus_set(load_experiment(write_experiment(dir, 8)), dir / "8",
                        testing::with_jobs(2));
  const AuditReport report = audit_stimulus_set(dir / "16" / "manifest.json");
  const std::vector<double> ref16 = lightness(dir / "16" / "cube/reference.png"),
                            ref8 = lightness(dir / "8" / "cube/reference.png");
  int compared = 0;
  double at_small = 0, at_large = 0;
  for (const StimulusAudit& s : report.stimuli) {
    if (s.reference) continue;
    if (s.lambda == 0) {
      EXPECT_FALSE(s.quantisation_loss.has_value());
      continue;
    }
    const std::vector<double> own16 = lightness(dir / "16" / s.file),
                              own8 = lightness(dir / "8" / s.file);
    double ideal = 0, error = 0;
    for (size_t p = 0; p < own16.size(); ++p) {
      const double change = own16[p] - ref16[p], rounded = own8[p] - ref8[p];
      ideal += change * change;
      error += (rounded - change) * (rounded - change);
    }
    ASSERT_TRUE(s.quantisation_loss.has_value()) << s.file;
    EXPECT_NEAR(*s.quantisation_loss, std::sqrt(error / ideal), 0.01) << s.file;
    if (std::abs(s.lambda - 0.05) < 1e-9) at_small = *s.quantisation_loss;
    if (s.lambda == 1) at_large = *s.quantisation_loss;
    ++compared;
  }
  EXPECT_EQ(compared, 20);
  EXPECT_GT(at_small, 0.25);  // the low end of the grid loses much at 8 bits ...
  EXPECT_LT(at_large, 0.1);   // ... the high end little
  bool noted = false;
  for (const std::string& note : report.notes)
    noted = noted || note.find("lambda 0.05 to") != std::string::npos;
  EXPECT_TRUE(noted) << "no note names the lambda range";
  // An 8-bit set has no ideal to compare with.
  for (const StimulusAudit& s : audit_stimulus_set(dir / "8" / "manifest.json").stimuli)
    EXPECT_FALSE(s.quantisation_loss);
}

}  // namespace
}  // namespace countershade
