// Texture-space filtering: the filters against analytic results, the mip pyramid filtered level by
// level (and cached), `texture` mode against a texture filtered beforehand, and parameter errors.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "core/file_bytes.h"
#include "enhance/filtered_pyramid.h"
#include "enhance/method.h"
#include "enhance/view_plan.h"
#include "stimuli/experiment.h"
#include "stimuli/stimulus_set.h"
#include "test_util.h"

namespace countershade {
namespace {

constexpr double kPi = std::numbers::pi;

std::vector<float> plane(int width, int height, const std::function<double(int, int)>& value) {
  std::vector<float> out(size_t(width) * size_t(height));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) out[size_t(y) * size_t(width) + size_t(x)] = float(value(x, y));
  return out;
}

// A Gaussian passes a sinusoid of period P with gain exp(−2π²σ²/P²), so unsharp masking's detail
// is (1 − that gain) times the sinusoid; wrapped borders make the periodic image exact.
TEST(LightnessFilters, UnsharpDetailOfASinusoidIsAnalytic) {
  const int period = 16;
  const auto L = plane(64, 8, [&](int x, int) { return 50 + 20 * std::sin(2 * kPi * x / period); });
  LightnessFilter f;
  f.sigma = 3;
  const auto d = lightness_detail(L, 64, 8, f, Borders::wrap);
  const double passed = std::exp(-2 * kPi * kPi * f.sigma * f.sigma / (period * period));
  for (int x = 0; x < 64; ++x)
    EXPECT_NEAR(d[size_t(3 * 64 + x)], (1 - passed) * 20 * std::sin(2 * kPi * x / period), 2e-3)
        << x;
}

TEST(LightnessFilters, BilateralKeepsAStepAndBlursLikeAGaussianWithAWideRange) {
  const auto step = plane(32, 4, [](int x, int) { return x < 16 ? 20.0 : 80.0; });
  LightnessFilter f;
  f.kind = FilterKind::bilateral;
  f.sigma = 2;
  f.sigma_r = 5;
  for (float d : lightness_detail(step, 32, 4, f, Borders::clamp))
    EXPECT_NEAR(d, 0.0, 1e-6);  // 60 L* ≫ σ_r
  // A flat range kernel leaves a Gaussian (over ±3σ): the detail is minus unsharp masking's.
  const auto wave = plane(64, 8, [](int x, int) { return 50 + 10 * std::sin(2 * kPi * x / 16); });
  f.sigma_r = 1e4;
  const auto d = lightness_detail(wave, 64, 8, f, Borders::wrap);
  const double passed = std::exp(-2 * kPi * kPi * f.sigma * f.sigma / (16 * 16));
  for (int x = 0; x < 64; ++x)
    EXPECT_NEAR(d[size_t(64 + x)], -(1 - passed) * 10 * std::sin(2 * kPi * x / 16), 0.05) << x;
}

TEST(LightnessFilters, DogDrawsLinesOnTheDarkSideOfAnEdgeOnly) {
  const auto step = plane(48, 4, [](int x, int) { return x < 24 ? 30.0 : 70.0; });
  LightnessFilter f;
  f.kind = FilterKind::dog;
  f.sigma = 1.5;
  const auto d = lightness_detail(step, 48, 4, f, Borders::clamp);
  const size_t row = 2 * 48;
  EXPECT_LT(d[row + 22], -5.0);  // just left of the edge, on the dark side: a line
  for (int x = 24; x < 48; ++x) EXPECT_EQ(d[row + size_t(x)], 0.0f) << x;  // the bright side: none
  EXPECT_EQ(d[row + 2], 0.0f);  // far from the edge: none
}

TextureLevel noise_level(int width, int height) {
  TextureLevel level{width, height, std::vector<glm::vec3>(size_t(width) * size_t(height))};
  for (size_t i = 0; i < level.texels.size(); ++i) {
    const double t = double((i * 2654435761u) % 1000) / 1000.0;
    level.texels[i] = glm::vec3(float(0.2 + 0.6 * t), float(0.3 + 0.3 * t), 0.25f);
  }
  return level;
}

// Each level of the mip-mode pyramid is the filter applied to the plain pyramid's level with σ in
// that level's texels; a second preparation reads the same numbers from the cache.
TEST(FilteredPyramid, MipModeFiltersEveryLevelWithSigmaInItsTexelsAndCachesIt) {
  testing::TempDir cache;
  const auto plain = std::make_shared<const Texture>(noise_level(64, 32));
  LightnessFilter f;
  f.kind = FilterKind::dog;
  const FilteredPyramid first = filter_pyramid(plain, TextureMode::mip, f, {1, 2}, cache.path());
  const Texture at = first.at(0.8);
  ASSERT_EQ(at.levels().size(), plain->levels().size());
  for (size_t k = 0; k < plain->levels().size(); ++k) {
    const TextureLevel& level = plain->levels()[k];
    const auto detail =
        lightness_detail(level_lightness(level), level.width, level.height, f, Borders::wrap);
    const TextureLevel expected = with_detail(level, detail, 0.8 * (k == 0 ? 1 : 2));
    for (size_t i = 0; i < expected.texels.size(); ++i)
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(at.levels()[k].texels[i][c], expected.texels[i][c], 1e-6) << k << " " << i;
  }
  const FilteredPyramid second = filter_pyramid(plain, TextureMode::mip, f, {1, 2}, cache.path());
  EXPECT_EQ(second.detail, first.detail);
  size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(cache.path() / "pyramids"))
    files += e.is_regular_file();
  EXPECT_EQ(files, 1u);
}

TEST(FilteredPyramid, ADamagedCacheFileIsRecomputed) {
  testing::TempDir cache;
  const auto plain = std::make_shared<const Texture>(noise_level(16, 16));
  const FilteredPyramid first = filter_pyramid(plain, TextureMode::mip, {}, {}, cache.path());
  for (const auto& e : std::filesystem::directory_iterator(cache.path() / "pyramids"))
    testing::write_file(e.path(), read_file_bytes(e.path()).substr(0, 100));
  EXPECT_EQ(filter_pyramid(plain, TextureMode::mip, {}, {}, cache.path()).detail, first.detail);
}

TEST(FilteredPyramid, StrengthZeroKeepsEveryTexel) {
  const TextureLevel level = noise_level(8, 8);
  const auto detail = lightness_detail(level_lightness(level), 8, 8, {}, Borders::wrap);
  EXPECT_EQ(with_detail(level, detail, 0.0).texels, level.texels);
}

TEST(TextureFilter, KeysOfAnotherFilterOrModeAreErrors) {
  EXPECT_EQ(testing::input_error_of([] {
              parse_method("texture-filter", {{"filter", "dog"}, {"sigma_r", 4}});
            }),
            "texture-filter: parameters.sigma_r: applies to filter bilateral only");
  EXPECT_EQ(testing::input_error_of([] {
              parse_method("texture-filter", {{"mode", "post"}, {"level_strengths", {1, 2}}});
            }),
            "texture-filter: parameters.level_strengths: applies to mode mip only");
  EXPECT_EQ(testing::input_error_of([] {
              parse_method("texture-filter", {{"filter", "bilateral"}, {"sigma", 20}});
            }),
            "texture-filter: parameters.sigma: must be at most 8 for filter bilateral (its cost "
            "grows with σ²)");
}

TEST(TextureFilter, AnUntexturedSceneIsRefusedBeforeAnythingRenders) {
  testing::TempDir dir;
  testing::write_file(
      dir / "ball.json",
      R"({"version": 1, "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "width": 16, "height": 12},
    "objects": [{"shape": {"type": "sphere"}}], "lights": [{"type": "directional", "direction": [0, 1, 1]}]})");
  const auto file = testing::write_file(
      dir / "e.json", R"({"version": 1, "scenes": [{"name": "ball", "file": "ball.json"}],
    "methods": [{"method": "texture-filter", "sigma": [1]}]})");
  const std::string error = testing::input_error_of(
      [&] { generate_stimulus_set(load_experiment(file), dir / "set", {}); });
  EXPECT_NE(error.find("texture-filter in mode mip filters textures, and no object of"),
            std::string::npos)
      << error;
  EXPECT_FALSE(std::filesystem::exists(dir / "set/ball"));
}

}  // namespace
}  // namespace countershade
