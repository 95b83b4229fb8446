// usm3d's stimuli are a property of the scene and the method, not of how the renderer draws its
// samples: a small bright light over a glossy ball, its sky drawn by the cosine (uneven: the few
// samples that find the light carry most of it, many times white) or by the cosine and the ball's
// specular lobe (even on the ball's highlight). The contrast C is formed from each
// surface's mean radiance before the display's clamp (docs/methods.md, "3D unsharp masking"); a
// clamp per sample made the cosine-sampled stimuli darker wherever the light reached.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/image.h"
#include "enhance/lightness.h"
#include "enhance/registry.h"
#include "enhance/view_plan.h"
#include "render/ray_tracer.h"
#include "render/scene_loader.h"
#include "test_util.h"

namespace countershade {
namespace {

// A dim sky with a small bright light (3×3 texels of a 64×32 map, about 17° across, 160 times the
// sky) high behind the viewer.
Image sky_with_a_small_light() {
  Image sky(64, 32, 3);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool light = std::abs(x - 28) <= 1 && std::abs(y - 7) <= 1;
      const float grey[3] = {0.25f, 0.3f, 0.4f};
      for (int c = 0; c < 3; ++c) sky.at(x, y, c) = light ? 40.0f : grey[c];
    }
  return sky;
}

std::string glossy_scene(const std::string& sampling, int seed) {
  return R"({
    "version": 1,
    "camera": {"eye": [0, 1.1, 3.0], "target": [0, 0.4, 0], "fov": 30, "width": 48, "height": 36},
    "render": {"seed": )" +
         std::to_string(seed) + R"(, "spp": 512},
    "objects": [
      {"name": "ground", "shape": {"type": "plane", "size": 6, "subdivisions": 24}, "material": {"albedo": 0.5}},
      {"name": "ball", "shape": {"type": "sphere", "radius": 0.45, "subdivisions": 4}, "transform": {"translate": [0, 0.45, 0]},
       "material": {"albedo": [0.6, 0.35, 0.25], "specular": {"model": "cook-torrance", "f0": 0.05, "roughness": 0.3}}}
    ],
    "lights": [{"type": "environment", "file": "sky.exr", "samples": 4, "sampling": ")" +
         sampling + R"(", "visible": false}],
    "display": {"exposure": -1.5}
  })";
}

struct Stimulus {
  std::vector<double> lightness;  // per pixel, of the 16-bit stimulus
  std::vector<int> object;        // per pixel, the G-buffer's
};

Stimulus stimulus_of(const Composed& out, const View& view) {
  Stimulus s;
  for (size_t p = 0; p < out.display.pixels.size() / 3; ++p)
    s.lightness.push_back(display_pixel_to_lab(&out.display.pixels[3 * p], view.encoding).L);
  s.object = view.render.gbuffer.object;
  return s;
}

// usm3d at λ = 3, and at λ = 0 (the reference) where asked.
Stimulus usm3d_stimulus(const testing::TempDir& dir, const std::string& sampling, int seed,
                        Stimulus* reference = nullptr) {
  const auto file = testing::write_file(dir / ("scene-" + std::to_string(seed) + ".json"),
                                        glossy_scene(sampling, seed));
  auto scene = std::make_shared<Scene>(load_scene(file));
  const nlohmann::json usm3d = {{"sigma", 0.15}};
  ViewOptions options;
  options.bits = 16;
  auto view = render_view(scene, plan_for("usm3d", usm3d, 3.0), options);
  const auto prepared = prepare_method("usm3d", view, usm3d);
  if (reference) *reference = stimulus_of(prepared->compose(0.0), *view);
  return stimulus_of(prepared->compose(3.0), *view);
}

double rms_difference(const Stimulus& a, const Stimulus& b) {
  double sum = 0;
  for (size_t p = 0; p < a.lightness.size(); ++p)
    sum += std::pow(a.lightness[p] - b.lightness[p], 2);
  return std::sqrt(sum / double(a.lightness.size()));
}

double mean_on(const Stimulus& s, int object) {
  double sum = 0;
  int n = 0;
  for (size_t p = 0; p < s.lightness.size(); ++p)
    if (s.object[p] == object) sum += s.lightness[p], ++n;
  return sum / n;
}

// "cosine" against "cosine+specular" at λ = 3: the ball's and the ground's mean within 0.5 L*,
// and the whole image's RMS difference within 1.5 times the two-seed noise of one sampling (a
// difference that is noise alone is about 1 times it).
TEST(Usm3dSampling, TheStimulusDoesNotDependOnHowTheSkyIsSampled) {
  testing::TempDir dir;
  write_image(dir / "sky.exr", sky_with_a_small_light());
  Stimulus reference;
  const Stimulus cosine = usm3d_stimulus(dir, "cosine", 1, &reference),
                 cosine_again = usm3d_stimulus(dir, "cosine", 2);
  const Stimulus mixture = usm3d_stimulus(dir, "cosine+specular", 1);
  const double noise = rms_difference(cosine, cosine_again);
  EXPECT_LE(rms_difference(cosine, mixture), 1.5 * noise) << "two-seed noise " << noise;
  EXPECT_NEAR(mean_on(cosine, 1), mean_on(mixture, 1), 0.5) << "the ball";
  EXPECT_NEAR(mean_on(cosine, 0), mean_on(mixture, 0), 0.5) << "the ground";
  // The control: the enhancement is there.
  EXPECT_GT(rms_difference(cosine, reference), 3.0);
}

}  // namespace
}  // namespace countershade
