// Mip-mapped textures: the pyramid's levels, the level a pixel's footprint picks, and that a
// minified pattern does not alias.

#include "render/texture.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "render/procedural_texture.h"
#include "render/ray_tracer.h"
#include "render/renderer.h"
#include "render/scene_loader.h"
#include "test_util.h"

namespace countershade {
namespace {

TextureLevel pattern(int width, int height, const std::function<float(int, int)>& value) {
  TextureLevel level{width, height, std::vector<glm::vec3>(size_t(width) * size_t(height))};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      level.texels[size_t(y) * size_t(width) + size_t(x)] = glm::vec3(value(x, y));
  return level;
}

double mean(const TextureLevel& level) {
  double sum = 0;
  for (const auto& t : level.texels) sum += t.x;
  return sum / double(level.texels.size());
}

TEST(Texture, EvenLevelsAreTwoByTwoMeansDownToOneTexel) {
  const Texture texture(pattern(8, 4, [](int x, int y) { return float(x + 10 * y); }));
  ASSERT_EQ(texture.levels().size(), 4u);  // 8×4, 4×2, 2×1, 1×1
  const TextureLevel& second = texture.levels()[1];
  EXPECT_EQ(second.width, 4);
  EXPECT_EQ(second.height, 2);
  EXPECT_FLOAT_EQ(second.at(1, 1).x, (22 + 23 + 32 + 33) / 4.0f);  // texels x 2…3, y 2…3
  EXPECT_EQ(texture.levels()[2].width, 2);
  EXPECT_EQ(texture.levels()[2].height, 1);
  EXPECT_NEAR(texture.levels()[3].at(0, 0).x, mean(texture.levels()[0]), 1e-5);
}

TEST(Texture, OddSizesKeepTheMeanByAreaWeights) {
  const Texture texture(pattern(7, 5, [](int x, int y) { return float((x * 37 + y * 11) % 9); }));
  ASSERT_EQ(texture.levels()[1].width, 3);
  ASSERT_EQ(texture.levels()[1].height, 2);
  for (const TextureLevel& level : texture.levels())
    EXPECT_NEAR(mean(level), mean(texture.levels()[0]), 1e-5);
}

TEST(Texture, WithoutFootprintOrMagnifiedTheLookupIsLevelZeroBilinear) {
  const Texture texture(pattern(16, 16, [](int x, int y) { return float((x ^ y) & 1); }));
  const glm::dvec2 uv(0.3, 0.71);
  EXPECT_EQ(texture.sample(uv, {0, 0}, {0, 0}), texture.levels()[0].bilinear(uv));
  EXPECT_EQ(texture.sample(uv, {0.5 / 16, 0}, {0, 0.9 / 16}), texture.levels()[0].bilinear(uv));
  EXPECT_DOUBLE_EQ(texture.level_of({4.0 / 16, 0}, {0, 4.0 / 16}), 2.0);
  EXPECT_DOUBLE_EQ(texture.level_of({100, 0}, {0, 100}), 4.0);  // clamped to the 1×1 level
}

// An elongated footprint takes several probes along its longer axis at the level of its shorter.
TEST(Texture, AnElongatedFootprintIsFilteredAnisotropically) {
  const Texture texture(
      pattern(64, 64, [](int x, int y) { return float(((x / 2) ^ (y / 2)) & 1); }));
  EXPECT_EQ(texture.probes_of({8.0 / 64, 0}, {0, 2.0 / 64}), 4);
  EXPECT_DOUBLE_EQ(texture.level_of({8.0 / 64, 0}, {0, 2.0 / 64}), 1.0);
  EXPECT_EQ(texture.probes_of({64.0 / 64, 0}, {0, 1.0 / 64}), Texture::kMaxAnisotropy);
  EXPECT_DOUBLE_EQ(texture.level_of({64.0 / 64, 0}, {0, 1.0 / 64}),
                   3.0);  // 64 texels over 8 probes
  // Four probes at level 1 along x, 2 texels apart: their mean.
  const glm::dvec2 uv(0.5, 0.5), dx(8.0 / 64, 0);
  glm::dvec3 mean(0.0);
  for (int i = 0; i < 4; ++i)
    mean += texture.levels()[1].bilinear(uv + dx * ((i + 0.5) / 4 - 0.5)) / 4.0;
  const glm::dvec3 got = texture.sample(uv, dx, {0, 2.0 / 64});
  EXPECT_NEAR(got.x, mean.x, 1e-12);
}

// The taps are what a lookup reads: Σ weight·texel is the lookup, for magnified, trilinear,
// anisotropic and coarsest-level footprints, with weights summing to 1.
TEST(Texture, TapsReproduceEveryKindOfLookup) {
  const Texture texture(
      pattern(37, 24, [](int x, int y) { return float((x * 13 + y * 7) % 11) / 10.0f; }));
  const std::vector<std::array<glm::dvec2, 3>> lookups = {
      {glm::dvec2(0.3, 0.7), glm::dvec2(0.0), glm::dvec2(0.0)},  // no footprint
      {glm::dvec2(0.99, 0.01), glm::dvec2(0.5 / 37, 0),
       glm::dvec2(0, 0.5 / 24)},  // magnified, at the wrap
      {glm::dvec2(0.41, 0.28), glm::dvec2(2.7 / 37, 0.4 / 24),
       glm::dvec2(-0.3 / 37, 3.1 / 24)},                                            // trilinear
      {glm::dvec2(0.12, 0.83), glm::dvec2(20.0 / 37, 0), glm::dvec2(0, 3.0 / 24)},  // anisotropic
      {glm::dvec2(0.5, 0.5), glm::dvec2(200.0 / 37, 0),
       glm::dvec2(0, 150.0 / 24)}};  // past the coarsest level
  for (const auto& [uv, dx, dy] : lookups) {
    std::vector<TextureTap> taps;
    texture.taps(uv, dx, dy, taps);
    double value = 0, weights = 0;
    for (const TextureTap& t : taps) {
      ASSERT_LT(t.level, texture.levels().size());
      ASSERT_LT(t.texel, texture.levels()[t.level].texels.size());
      value += t.weight * texture.levels()[t.level].texels[t.texel].x;
      weights += t.weight;
    }
    EXPECT_NEAR(value, texture.sample(uv, dx, dy).x, 1e-12) << uv.x << " " << dx.x;
    EXPECT_NEAR(weights, 1.0, 1e-12);
  }
}

TEST(ProceduralTexture, CheckerNoiseAlternatesSquaresStaysInRangeAndFollowsItsSeed) {
  const TextureLevel a = checker_noise({64, 4, 0.35, 1}), b = checker_noise({64, 4, 0.35, 2});
  EXPECT_EQ(a.texels, checker_noise({64, 4, 0.35, 1}).texels);
  EXPECT_NE(a.texels, b.texels);
  double light = 0, dark = 0;
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) light += a.at(x, y).x, dark += a.at(x + 16, y).x;
  EXPECT_GT(light, 2 * dark);  // the square at the origin is light, its neighbour dark
  for (const glm::vec3& t : a.texels)
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(t[c] >= 0 && t[c] <= 1);
}

// A square plane (size 2, UVs over [0,1]²) seen head-on from `distance`, lit by a constant
// ambient radiance of 1 so that each pixel's radiance is the albedo it looked up.
Scene head_on_plane(double distance, int pixels) {
  testing::TempDir dir;
  const std::string json =
      R"({"version": 1,
    "camera": {"eye": [0, )" +
      std::to_string(distance) + R"(, 0], "target": [0, 0, 0], "up": [0, 0, -1], "fov": 40,
               "width": )" +
      std::to_string(pixels) + ", \"height\": " + std::to_string(pixels) + R"(},
    "render": {"spp": 1},
    "display": {"background": [0, 0, 0]},
    "objects": [{"name": "plane", "shape": {"type": "plane", "size": 2, "subdivisions": 1}}],
    "lights": [{"type": "ambient", "radiance": 1}]})";
  return load_scene(testing::write_file(dir / "plane.json", json));
}

double centre_radiance(const Scene& scene) {
  const RayTracer tracer(scene);
  const RenderResult result = render(scene, tracer, {});
  const int w = result.radiance.width, h = result.radiance.height;
  return result.radiance.at(w / 2, h / 2, 0);
}

// Level k of this pyramid holds the constant k/16, so a trilinear lookup returns level/16.
TEST(Texture, APlaneAtAKnownDistanceSamplesTheExpectedLevel) {
  std::vector<TextureLevel> levels;
  for (int size = 256, k = 0; size >= 1; size /= 2, ++k)
    levels.push_back(pattern(size, size, [k](int, int) { return float(k) / 16.0f; }));
  const auto texture = std::make_shared<const Texture>(Texture::from_levels(std::move(levels)));
  for (double distance : {1.5, 3.0, 6.0}) {
    Scene scene = head_on_plane(distance, 64);
    scene.objects[0].material.texture = texture;
    // A pixel at the centre spans 2·d·tan(20°)/64 world units; the texture has 256 texels per 2.
    const double expected =
        std::log2(2 * distance * std::tan(20 * std::numbers::pi / 180) / 64 * 128);
    EXPECT_NEAR(16 * centre_radiance(scene), expected, 0.5) << "distance " << distance;
    EXPECT_NEAR(16 * centre_radiance(scene), expected, 0.05) << "distance " << distance;
  }
}

// The RMS of the centre 32×32 pixels about their mean.
double centre_ac_rms(const Scene& scene) {
  const RayTracer tracer(scene);
  const Image image = render(scene, tracer, {}).radiance;
  double sum = 0, sum2 = 0;
  for (int y = 16; y < 48; ++y)
    for (int x = 16; x < 48; ++x) {
      sum += image.at(x, y, 0);
      sum2 += double(image.at(x, y, 0)) * image.at(x, y, 0);
    }
  const double n = 32 * 32, m = sum / n;
  return std::sqrt(std::max(0.0, sum2 / n - m * m));
}

// A 0/1 checkerboard of 3-texel squares (period 6 texels, RMS 0.5 about its mean) seen at 3 to 8
// texels per pixel: its fundamental (≥ 0.5 cycles per pixel) lies at or above the pixel Nyquist
// frequency, so everything it leaves in a one-sample-per-pixel image is aliasing. A box pyramid
// leaves the most at whole levels (4 texels per pixel: RMS ratio 0.16).
TEST(Texture, AMinifiedCheckerboardDoesNotAlias) {
  const TextureLevel checker =
      pattern(512, 512, [](int x, int y) { return float(((x / 3) + (y / 3)) % 2); });
  for (double texels_per_pixel : {3.0, 4.0, 5.3, 8.0}) {
    const double distance =
        texels_per_pixel * 64 / (2 * std::tan(20 * std::numbers::pi / 180) * 256);
    Scene scene = head_on_plane(distance, 64);
    scene.objects[0].material.texture =
        std::make_shared<const Texture>(Texture::from_levels({checker}));
    const double single_level = centre_ac_rms(scene) / 0.5;
    scene.objects[0].material.texture = std::make_shared<const Texture>(checker);
    const double pyramid = centre_ac_rms(scene) / 0.5;
    EXPECT_GT(single_level, 0.3)
        << texels_per_pixel;  // without the pyramid the pattern aliases into the image
    // The stated bound (docs/enhancement-methods.md): the aliased energy is below 4 % of the
    // pattern's.
    EXPECT_LT(pyramid * pyramid, 0.04)
        << texels_per_pixel << " texels per pixel: RMS ratio " << pyramid
        << " (without the pyramid " << single_level << ")";
  }
}

}  // namespace
}  // namespace countershade
