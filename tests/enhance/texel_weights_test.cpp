// Texel weights: a render's pixels as a linear function of its texels. With the render's own
// samples, the weights give what rendering with changed texels gives (every kind of light,
// ambient occlusion, a glossy material, a repeated texture), and texture-filter's λ composed from
// them matches its λ rendered again.

#include "enhance/texel_weights.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include "enhance/method.h"
#include "enhance/view.h"
#include "enhance/view_plan.h"
#include "render/rich_scene.h"
#include "test_util.h"

namespace countershade {
namespace {

// Every texel of the material's texture at half its value, in every level.
class HalfTexture final : public TextureHook {
 public:
  explicit HalfTexture(const Texture& plain) {
    std::vector<TextureLevel> levels = plain.levels();
    for (auto& level : levels)
      for (auto& texel : level.texels) texel *= 0.5f;
    half_ = Texture::from_levels(std::move(levels));
  }
  const Texture* texture(unsigned, const Material& material) const override {
    return material.texture ? &half_ : nullptr;
  }

 private:
  Texture half_;
};

std::shared_ptr<const View> recorded_view(std::shared_ptr<const Scene> scene) {
  RenderOptions options;
  options.threads = 2;
  options.record_trace = true;
  auto tracer = std::make_shared<const RayTracer>(*scene);
  return make_view(scene, tracer, render(*scene, *tracer, options));
}

TEST(TexelWeights, ChangedTexelsGiveWhatRenderingWithThemGives) {
  testing::TempDir dir;
  for (const auto& scene : {testing::fixed_count_scene(dir), testing::rich_scene(dir)}) {
    const auto view = recorded_view(scene);
    const Texture& plain = *scene->objects[0].material.texture;
    const auto weights = TexelWeights::of_view(*view, {&plain}, 2);
    ASSERT_GT(weights->texels().size(), 100u);
    std::vector<glm::dvec3> change;
    for (const auto& t : weights->texels())
      change.push_back(-0.5 * glm::dvec3(plain.levels()[t.level].texels[t.index]));
    const Image composed = weights->radiance_with(view->render.radiance, change, 2);
    // The same samples, each shaded with the halved texture (the log replays them all).
    RenderOptions options;
    options.threads = 2;
    options.replay_trace = view->render.trace;
    options.texture_hook = std::make_shared<HalfTexture>(plain);
    const RenderResult rendered = render(*scene, *view->tracer, options);
    size_t changed = 0;
    for (size_t i = 0; i < composed.pixels.size(); ++i) {
      const double expected = rendered.radiance.pixels[i];
      changed += std::abs(expected - view->render.radiance.pixels[i]) > 1e-3;
      // Where the replay sampled further (adaptive), the pixels differ by their sampling noise.
      if (rendered.spp[i / 3] == view->render.spp[i / 3]) {
        ASSERT_NEAR(composed.pixels[i], expected, 1e-5 * std::max(1.0, expected)) << i;
      }
    }
    EXPECT_GT(changed, composed.pixels.size() / 4);  // the floor covers much of the image
    // Without the log the samples are traced again: the same weights.
    auto untraced = std::make_shared<View>(*view);
    untraced->render.trace = nullptr;
    EXPECT_EQ(TexelWeights::of_view(*untraced, {&plain}, 2)
                  ->radiance_with(view->render.radiance, change, 2)
                  .pixels,
              composed.pixels);
    // Weights that would outgrow their limit are given up.
    EXPECT_EQ(TexelWeights::of_view(*view, {&plain}, 2, 16 * (weights->entries() - 1)), nullptr);
    EXPECT_NE(TexelWeights::of_view(*view, {&plain}, 2, 16 * weights->entries()), nullptr);
    // No change: the view's radiance, bit for bit.
    EXPECT_EQ(
        weights->radiance_with(view->render.radiance, std::vector<glm::dvec3>(change.size()), 2)
            .pixels,
        view->render.radiance.pixels);
  }
}

// In a stimulus set (compose_from_samples) texture-filter composes each λ from the view's samples;
// `render` renders it again. At a fixed sample count the two take the same samples, so their
// stimuli agree but for the rare code that rounding puts on the other side of a level.
TEST(TexelWeights, TextureFilterComposedFromSamplesMatchesRenderingAgain) {
  testing::TempDir dir;
  ::setenv("COUNTERSHADE_CACHE", (dir / "cache").c_str(), 1);
  const auto scene = testing::fixed_count_scene(dir);
  for (const std::string mode : {"mip", "texture"}) {
    const nlohmann::json parameters{{"mode", mode}, {"filter", "unsharp"}, {"sigma", 1}};
    const auto view = render_view(scene, plan_for("texture-filter", parameters, 2.0), {8, 2, {}});
    const MethodUse use = parse_method("texture-filter", parameters);
    PrepareContext again = make_use_context(view, 0, 2), composed = again;
    composed.compose_from_samples = true;
    const auto rendering = use.method->prepare(again, *use.parameters);
    const auto composing = use.method->prepare(composed, *use.parameters);
    EXPECT_EQ(composing->compose(0).display.pixels, view->display.pixels);
    for (double lambda : {0.5, 2.0}) {
      const Image a = rendering->compose(lambda).display, b = composing->compose(lambda).display;
      size_t differing = 0, changed = 0;
      for (size_t i = 0; i < a.pixels.size(); ++i) {
        differing += a.pixels[i] != b.pixels[i];
        ASSERT_LE(std::abs(a.pixels[i] - b.pixels[i]), 1.01 / 255)
            << mode << " λ " << lambda << " at " << i;
        changed += b.pixels[i] != view->display.pixels[i];
      }
      EXPECT_LE(differing, a.pixels.size() / 1000) << mode << " λ " << lambda;
      EXPECT_GT(changed, a.pixels.size() / 20) << mode << " λ " << lambda;
    }
  }
}

}  // namespace
}  // namespace countershade
