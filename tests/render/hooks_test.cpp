// The rendering hooks: a shading hook changes how light is reflected but never what is in
// shadow; a texture hook replaces what a material samples; without hooks nothing changes.

#include "render/hooks.h"

#include <gtest/gtest.h>

#include <cmath>

#include "enhance/method.h"
#include "enhance/view_plan.h"
#include "render/scene_loader.h"
#include "render/shading.h"
#include "test_util.h"

namespace countershade {
namespace {

// A lit floor with a box casting a hard shadow on it, seen from above.
const char* kShadowScene = R"({
  "version": 1,
  "camera": {"eye": [0, 6, 0.01], "target": [0, 0, 0], "projection": "orthographic", "height_world": 4,
             "width": 64, "height": 64},
  "render": {"spp": 1},
  "objects": [{"name": "floor", "shape": {"type": "plane", "size": 4, "subdivisions": 8}, "material": {"albedo": 0.6}},
              {"name": "box", "shape": {"type": "box", "size": [0.8, 1.5, 0.8]}, "transform": {"translate": [0, 0.75, 0]}}],
  "lights": [{"type": "directional", "direction": [1, 0.6, 0], "irradiance": 2}]
})";

class PlainHook final : public ShadingHook {
 public:
  glm::dvec3 reflect(const ShadingInputs& s, const glm::dvec3& wi,
                     const glm::dvec3& incident) const override {
    return reflect_plain(s, wi, incident);
  }
};

// Shades as if every light came straight along the normal, optionally fading out over a band of
// the terminator. With `dark_side`, it shades the dark side too, where the light mirrored across
// the tangent plane is open (as exaggerated shading does).
class HeadOnHook final : public ShadingHook {
 public:
  explicit HeadOnHook(double band = 0, bool dark_side = false)
      : band_(band), dark_side_(dark_side) {}
  glm::dvec3 reflect(const ShadingInputs& s, const glm::dvec3&,
                     const glm::dvec3& incident) const override {
    return reflect_plain(s, s.normal, incident);
  }
  bool shades_dark_side() const override { return dark_side_; }
  std::optional<glm::dvec3> dark_side_direction(const ShadingInputs& s,
                                                const glm::dvec3& wi) const override {
    return wi - 2 * glm::dot(s.normal, wi) * s.normal;
  }
  double terminator_band() const override { return band_; }

 private:
  double band_;
  bool dark_side_;
};

class ConstantTexture final : public TextureHook {
 public:
  ConstantTexture() : texture_(TextureLevel{1, 1, {glm::vec3(0.25f, 0.5f, 0.75f)}}) {}
  const Texture* texture(unsigned, const Material&) const override { return &texture_; }

 private:
  Texture texture_;
};

std::shared_ptr<const View> base_view(const testing::TempDir& dir, const std::string& json) {
  return render_view(std::make_shared<Scene>(load_scene(testing::write_file(dir / "s.json", json))),
                     {}, {});
}

TEST(Hooks, APlainShadingHookRendersThePlainImage) {
  testing::TempDir dir;
  auto view = base_view(dir, kShadowScene);
  RenderRequest request;
  request.shading_hook = std::make_shared<PlainHook>();
  auto hooked = make_context(view).render_again(request);
  const auto& a = view->render.radiance.pixels;
  const auto& b = hooked->render.radiance.pixels;
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) ASSERT_NEAR(a[i], b[i], 1e-6 * (1.0 + a[i])) << i;
}

TEST(Hooks, AShadingHookChangesShadingButNotShadows) {
  testing::TempDir dir;
  auto view = base_view(dir, kShadowScene);
  RenderRequest request;
  request.shading_hook = std::make_shared<HeadOnHook>();
  auto hooked = make_context(view).render_again(request);
  const GBuffer& g = view->render.gbuffer;
  int shadow = 0, lit = 0;
  const double head_on = 0.6 / M_PI * 2.0;  // albedo/π · irradiance · cos 0
  for (size_t i = 0; i < g.object.size(); ++i) {
    if (g.object[i] != 0) continue;  // the floor only
    const float before = view->render.radiance.pixels[3 * i],
                after = hooked->render.radiance.pixels[3 * i];
    if (before == 0.0f) {  // in the box's shadow: stays dark
      EXPECT_EQ(after, 0.0f) << i;
      ++shadow;
    } else {  // lit: now as if lit head-on, brighter than the grazing light
      EXPECT_NEAR(after, head_on, 1e-5) << i;
      EXPECT_GT(after, before);
      ++lit;
    }
  }
  EXPECT_GT(shadow, 50);
  EXPECT_GT(lit, 500);
}

TEST(Hooks, TheTerminatorFadeRisesSmoothlyFromZeroToOne) {
  const double band = 0.25;
  EXPECT_EQ(terminator_fade(-0.5, band), 0.0);
  EXPECT_EQ(terminator_fade(0.0, band), 0.0);
  EXPECT_EQ(terminator_fade(band, band), 1.0);
  EXPECT_EQ(terminator_fade(0.9, band), 1.0);
  EXPECT_DOUBLE_EQ(terminator_fade(0.5 * band, band), 0.5);
  const double h = 1e-6;  // flat at both ends: no kink where the fade starts or ends
  EXPECT_LT(terminator_fade(h, band) / h, 1e-4);
  EXPECT_LT((1 - terminator_fade(band - h, band)) / h, 1e-4);
  for (double c = 0; c < band; c += 0.01)
    EXPECT_LT(terminator_fade(c, band), terminator_fade(c + 0.01, band));
  // No band: the whole change wherever the light faces the normal, none behind it.
  EXPECT_EQ(terminator_fade(1e-9, 0.0), 1.0);
  EXPECT_EQ(terminator_fade(0.0, 0.0), 0.0);
  EXPECT_EQ(terminator_fade(-0.3, 0.0), 0.0);
}

// Light grazing the floor at cos 0.1, inside a terminator band of 0.25: the hook's change is faded
// in by terminator_fade(0.1, 0.25), so the floor lies between the plain and the head-on shading.
// Without a band (the default) the floor is shaded head-on.
TEST(Hooks, AHookChangesLightNearTheTerminatorOnlyInPartWithABand) {
  testing::TempDir dir;
  std::string scene = kShadowScene;
  const double cos_i = 0.1, sin_i = std::sqrt(1 - cos_i * cos_i);
  scene.replace(scene.find("[1, 0.6, 0]"), 11,
                "[" + std::to_string(sin_i) + ", " + std::to_string(cos_i) + ", 0]");
  auto view = base_view(dir, scene);
  RenderRequest request;
  request.shading_hook = std::make_shared<HeadOnHook>(0.25);
  auto faded = make_context(view).render_again(request);
  request.shading_hook = std::make_shared<HeadOnHook>();
  auto whole = make_context(view).render_again(request);
  const GBuffer& g = view->render.gbuffer;
  const double plain = 0.6 / M_PI * 2.0 * cos_i, head_on = 0.6 / M_PI * 2.0;
  const double expected = plain + terminator_fade(cos_i, 0.25) * (head_on - plain);
  ASSERT_LT(expected, 0.5 * head_on);
  int lit = 0;
  for (size_t i = 0; i < g.object.size(); ++i) {
    if (g.object[i] != 0 || view->render.radiance.pixels[3 * i] == 0.0f) continue;
    EXPECT_NEAR(view->render.radiance.pixels[3 * i], plain, 1e-5);
    EXPECT_NEAR(faded->render.radiance.pixels[3 * i], expected, 1e-5) << i;
    EXPECT_NEAR(whole->render.radiance.pixels[3 * i], head_on, 1e-5) << i;
    ++lit;
  }
  EXPECT_GT(lit, 500);
}

// The floor lit from below: the plain render leaves all of it on the light's dark side, black. A
// hook that shades the dark side lights it wherever the direction it shades with is open: here
// the light mirrored above the floor, so the box's shadow is the one the mirrored light casts in a
// plain render. A hook that keeps the dark side dark, or fades over a band, leaves it black.
TEST(Hooks, AHookMayShadeTheDarkSideWhereItsOwnDirectionIsOpen) {
  testing::TempDir below, above;
  std::string from_below = kShadowScene;
  from_below.replace(from_below.find("[1, 0.6, 0]"), 11, "[1, -0.6, 0]");
  auto view = base_view(below, from_below);
  auto mirrored = base_view(above, kShadowScene);
  auto hooked_with = [&](std::shared_ptr<const ShadingHook> hook) {
    RenderRequest request;
    request.shading_hook = std::move(hook);
    return make_context(view).render_again(request);
  };
  auto dark_side = hooked_with(std::make_shared<HeadOnHook>(0.0, true));
  auto head_on = hooked_with(std::make_shared<HeadOnHook>());
  auto banded = hooked_with(std::make_shared<HeadOnHook>(0.25, true));
  const GBuffer& g = view->render.gbuffer;
  const double lit_value = 0.6 / M_PI * 2.0;
  int lit = 0, shadow = 0;
  for (size_t i = 0; i < g.object.size(); ++i) {
    if (g.object[i] != 0) continue;
    ASSERT_EQ(view->render.radiance.pixels[3 * i], 0.0f) << i;
    EXPECT_EQ(head_on->render.radiance.pixels[3 * i], 0.0f) << i;
    EXPECT_EQ(banded->render.radiance.pixels[3 * i], 0.0f) << i;
    const float after = dark_side->render.radiance.pixels[3 * i];
    if (mirrored->render.radiance.pixels[3 * i] == 0.0f) {
      EXPECT_EQ(after, 0.0f) << i;
      ++shadow;
    } else if (mirrored->render.radiance.pixels[3 * i] >
               0.99f * float(0.6 / M_PI * 2.0 * 0.6 / std::sqrt(1.36))) {
      EXPECT_NEAR(after, lit_value, 1e-5) << i;
      ++lit;
    }
  }
  EXPECT_GT(shadow, 50);
  EXPECT_GT(lit, 500);
}

TEST(Hooks, ATextureHookReplacesWhatTheMaterialSamples) {
  testing::TempDir dir;
  std::string scene = kShadowScene;
  auto view = base_view(dir, scene);
  RenderRequest request;
  request.texture_hook = std::make_shared<ConstantTexture>();
  auto hooked = make_context(view).render_again(request);
  const GBuffer& g = view->render.gbuffer;
  for (size_t i = 0; i < g.object.size(); ++i) {
    if (g.object[i] != 0 || view->render.radiance.pixels[3 * i] == 0.0f) continue;
    // Albedo 0.6 before; (0.25, 0.5, 0.75) after: each channel scales by its ratio.
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(hooked->render.radiance.pixels[3 * i + c],
                  view->render.radiance.pixels[3 * i + c] * (0.25 + 0.25 * c) / 0.6, 1e-5);
  }
}

}  // namespace
}  // namespace countershade
