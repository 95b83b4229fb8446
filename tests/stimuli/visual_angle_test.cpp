// Sizes in degrees of visual angle: the screen's pixels per degree, σ and image sizes given in
// degrees (the same bytes as in pixels), and what the manifest records.

#include "core/visual_angle.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "core/error.h"
#include "core/file_bytes.h"
#include "stimuli/experiment.h"
#include "stimuli/set_test_util.h"
#include "stimuli/stimulus_set.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

constexpr char kScreen[] = R"("screen": {"width_mm": 531.4, "width_px": 1920, "distance_mm": 570})";

// 2·570·tan(0.5°)·1920/531.4 = 35.9454 pixels per degree.
TEST(VisualAngle, OneDegreeOnAReferenceScreen) {
  EXPECT_NEAR(pixels_per_degree(531.4, 1920, 570), 35.9454, 1e-4);
  EXPECT_NEAR(pixels_per_degree(531.4, 1920, 570), 35.94, 0.01);
  // Twice the distance, twice the pixels; twice the width in mm, half.
  EXPECT_DOUBLE_EQ(pixels_per_degree(531.4, 1920, 1140), 2 * pixels_per_degree(531.4, 1920, 570));
  EXPECT_DOUBLE_EQ(pixels_per_degree(1062.8, 1920, 570), 0.5 * pixels_per_degree(531.4, 1920, 570));
}

// The cube under usm2d and depth-usm with σ in degrees, and the same with σ in pixels: the same
// bytes. The image size in degrees becomes the nearest whole number of pixels.
TEST(VisualAngle, SigmaInDegreesGivesTheSameStimuliAsInPixels) {
  testing::TempDir dir;
  testing::write_file(dir / "cube.json", testing::kLitCubeScene);
  const double ppd = pixels_per_degree(531.4, 1920, 570), sigma_px = 0.05 * ppd;
  char pixels[64];
  std::snprintf(pixels, sizeof pixels, "%.17g", sigma_px);
  auto experiment = [&](const std::string& name, const std::string& size,
                        const std::string& sigma) {
    return load_experiment(testing::write_file(
        dir / (name + ".json"), R"({"version": 1, "name": ")" + name + R"(", "seed": 3,
      )" + std::string(kScreen) + R"(, "lambda": {"min": 0, "max": 1, "step": 1},
      "scenes": [{"name": "cube", "file": "cube.json", )" +
                                    size + R"(}],
      "methods": [{"method": "usm2d", )" +
                                    sigma + R"(}, {"method": "depth-usm", "operator": "darken", )" +
                                    sigma + R"(}]})"));
  };
  const Experiment degrees =
      experiment("degrees", R"("width_deg": 2.5, "height_deg": 2)", R"("sigma_deg": [0.05])");
  const Experiment px = experiment("pixels", R"("width": 90, "height": 72)",
                                   std::string(R"("sigma_px": [)") + pixels + "]");
  EXPECT_EQ(degrees.scenes[0].width, 90);   // 2.5° × 35.945 = 89.9
  EXPECT_EQ(degrees.scenes[0].height, 72);  // 2° × 35.945 = 71.9
  generate_stimulus_set(degrees, dir / "a", testing::with_jobs(2));
  generate_stimulus_set(px, dir / "b", testing::with_jobs(2));
  const OrderedJson a = testing::manifest_json(dir / "a"), b = testing::manifest_json(dir / "b");
  ASSERT_EQ(a["stimuli"].size(), b["stimuli"].size());
  for (size_t i = 0; i < a["stimuli"].size(); ++i) {
    EXPECT_EQ(a["stimuli"][i]["sha256"], b["stimuli"][i]["sha256"]) << a["stimuli"][i]["file"];
    if (a["stimuli"][i]["method"] != "none") {
      EXPECT_EQ(a["stimuli"][i]["sigma_kind"], "sigma_deg");
    }
  }
  EXPECT_NEAR(a["viewing"]["pixels_per_degree"].get<double>(), ppd, 1e-12);
  EXPECT_EQ(a["viewing"]["screen"]["distance_mm"], 570.0);
}

TEST(VisualAngle, DegreesWithoutAScreenAreRefused) {
  testing::TempDir dir;
  testing::write_file(dir / "cube.json", testing::kLitCubeScene);
  const fs::path file = testing::write_file(
      dir / "e.json", R"({"version": 1, "lambda": {"min": 0, "max": 1, "step": 1},
    "scenes": [{"name": "cube", "file": "cube.json"}], "methods": [{"method": "usm2d", "sigma_deg": [0.1]}]})");
  try {
    load_experiment(file);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "sigma_deg: a size in degrees needs the experiment's \"screen\" block"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace countershade
