// The noise budget as an observer meets it: the preview scenes of the ritschel2008 set, rendered
// twice with different seeds under the default budget. The L* difference of the two written
// images, over √2, is the measured sampling noise of one; for the reference and for usm3d at
// λ = 3, σ = 0.12 it meets the budget (RMS ≤ 0.5, p99 ≤ 2), and the manifest's estimate agrees
// with it within 30 %. The scenes are rendered at 128×96, a quarter of the preview's size in each
// direction: their budget holds the image's RMS (`"allocation": "image"`), a mean over pixels that
// adaptive sampling meets at any size, so the measure is the same at a fraction of the cost (the
// full-size figures are in docs/experiments/ritschel2008.md). They measure 0.38 to 0.45 L* at
// λ = 3 and 0.11 to 0.14 for the references: the allocation's tenth in hand is what keeps them
// under 0.5.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "core/display.h"
#include "core/image.h"
#include "enhance/lightness.h"
#include "stimuli/stimulus_set.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

struct Measured {
  double rms = 0, p99 = 0;
};

// RMS and 99th percentile over pixels of |L*a − L*b| / √2 between two written sRGB images.
Measured two_seed_noise(const fs::path& a, const fs::path& b) {
  const Image ia = read_image(a), ib = read_image(b);
  const DisplayEncoding srgb = DisplayEncoding::srgb();
  std::vector<double> d(size_t(ia.width) * ia.height);
  double sum = 0;
  for (size_t p = 0; p < d.size(); ++p) {
    d[p] = std::abs(display_pixel_to_lab(&ia.pixels[3 * p], srgb).L -
                    display_pixel_to_lab(&ib.pixels[3 * p], srgb).L) /
           std::sqrt(2.0);
    sum += d[p] * d[p];
  }
  std::sort(d.begin(), d.end());
  return {std::sqrt(sum / double(d.size())), d[size_t(0.99 * double(d.size() - 1))]};
}

// One preview scene at 128×96 (pixels enough for the RMS and the 99th percentile of the noise, at a
// quarter of the preview's cost), the reference and usm3d (σ = 0.12) on the grid {0, 3}, with the
// given seed.
fs::path generate(const testing::TempDir& dir, const std::string& scene, int seed) {
  const fs::path scene_file =
      testing::source_dir() / "experiments/ritschel2008/scenes" / (scene + ".json");
  const std::string name = "seed-" + std::to_string(seed);
  const fs::path experiment =
      testing::write_file(dir / (name + ".json"), R"({
    "version": 1, "name": "noise", "seed": )" + std::to_string(seed) +
                                                      R"(,
    "lambda": {"min": 0, "max": 3, "step": 3},
    "scenes": [{"name": ")" + scene + R"(", "file": ")" +
                                                      scene_file.string() +
                                                      R"(", "width": 128, "height": 96}],
    "methods": [{"method": "usm3d", "sigma": [0.12], "ring_samples": 3}]
  })");
  GenerateOptions options;
  generate_stimulus_set(load_experiment(experiment), dir / name, options);
  return dir / name;
}

nlohmann::json manifest_entry(const fs::path& set, const std::string& file) {
  std::ifstream in(set / "manifest.json");
  const nlohmann::json manifest = nlohmann::json::parse(in);  // alive while iterating
  for (const auto& s : manifest["stimuli"])
    if (s["file"] == file) return s;
  ADD_FAILURE() << "no " << file << " in " << set / "manifest.json";
  return {};
}

class PreviewSceneNoise : public ::testing::TestWithParam<std::string> {};

TEST_P(PreviewSceneNoise, MeetsTheBudgetAndTheManifestSaysSo) {
  testing::TempDir dir;
  const std::string scene = GetParam();
  const fs::path a = generate(dir, scene, 11), b = generate(dir, scene, 12);
  for (const std::string image : {"reference.png", "usm3d/sigma-0.12/lambda-3.png"}) {
    const std::string file = scene + "/" + image;
    const Measured measured = two_seed_noise(a / file, b / file);
    EXPECT_LE(measured.rms, 0.5) << file;
    EXPECT_LE(measured.p99, 2.0) << file;
    for (const fs::path& set : {a, b}) {
      const nlohmann::json entry = manifest_entry(set, file);
      const double estimate = entry["noise"]["rms"].get<double>();
      EXPECT_NEAR(estimate, measured.rms, 0.3 * measured.rms) << file << ": estimated " << estimate;
      EXPECT_TRUE(entry["noise"]["budget"]["met"].get<bool>()) << file;
      EXPECT_LE(entry["spp"]["min"].get<int>(), entry["spp"]["mean"].get<double>()) << file;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Ritschel2008, PreviewSceneNoise,
                         ::testing::Values("chamfer", "dice", "scan", "clutter"));

}  // namespace
}  // namespace countershade
