// Replaying a render's rays: a render that records its ray answers (and its shading records) gives
// the plain image, and a render with hooks that reads them back gives, bit for bit, the image it
// gives by tracing, with (almost) no rays traced. The scene uses every kind of light, soft shadows,
// ambient occlusion, a texture, a glossy material and adaptive sampling, so that every shadow-ray
// path is exercised.

#include "render/trace_log.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <glm/geometric.hpp>

#include "enhance/method.h"
#include "enhance/view.h"
#include "enhance/view_plan.h"
#include "render/hooks.h"
#include "render/rich_scene.h"
#include "test_util.h"

namespace countershade {
namespace {

using testing::fixed_count_scene;
using testing::rich_scene;

// Shades every light sample as if it came from a direction tilted towards the viewer: it uses
// shadow answers the plain path never asks (light from behind the shading normal) and the
// specular lobe.
class TiltHook final : public ShadingHook {
 public:
  glm::dvec3 reflect(const ShadingInputs& s, const glm::dvec3& wi,
                     const glm::dvec3& incident) const override {
    return 0.8 * reflect_plain(s, glm::normalize(wi + 0.6 * s.wo + 0.3 * s.normal), incident);
  }
};

class HalfTexture final : public TextureHook {
 public:
  const Texture* texture(unsigned, const Material& material) const override {
    if (!material.texture) return nullptr;
    if (!half_) {
      TextureLevel level = material.texture->levels().front();
      for (auto& texel : level.texels) texel *= 0.5f;
      half_ = std::make_unique<Texture>(level);
    }
    return half_.get();
  }

 private:
  mutable std::unique_ptr<Texture> half_;  // made on the first (single-threaded) call below
};

// `radiance_only`: as a method's render of one λ, which keeps nothing else.
RenderResult render_with(const Scene& scene, const RayTracer& tracer,
                         std::shared_ptr<const ShadingHook> hook,
                         std::shared_ptr<const TraceLog> replay = nullptr, bool record = false,
                         bool radiance_only = false) {
  RenderOptions options;
  options.threads = 2;
  options.shading_hook = std::move(hook);
  options.replay_trace = std::move(replay);
  options.record_trace = record;
  options.radiance_only = radiance_only;
  return render(scene, tracer, options);
}

void expect_same_pixels(const RenderResult& a, const RenderResult& b) {
  ASSERT_EQ(a.radiance.pixels.size(), b.radiance.pixels.size());
  size_t differing = 0;
  for (size_t i = 0; i < a.radiance.pixels.size(); ++i)
    differing += a.radiance.pixels[i] != b.radiance.pixels[i];
  EXPECT_EQ(differing, 0u);
  EXPECT_EQ(a.spp, b.spp);
}

TEST(TraceLog, RecordingTheRaysLeavesThePlainImageUnchanged) {
  testing::TempDir dir;
  auto scene = rich_scene(dir);
  const RayTracer tracer(*scene);
  const RenderResult plain = render_with(*scene, tracer, nullptr);
  const RenderResult recorded = render_with(*scene, tracer, nullptr, nullptr, true);
  expect_same_pixels(plain, recorded);
  EXPECT_EQ(plain.trace, nullptr);
  ASSERT_NE(recorded.trace, nullptr);
  EXPECT_GT(recorded.sampling.rounds, 1);  // adaptive: the log spans several rounds
  // Recording asks the shadow rays a hook could use as well: never fewer than the plain path.
  EXPECT_GE(recorded.rays.shadow, plain.rays.shadow);
}

TEST(TraceLog, AReplayedRenderWithAShadingHookEqualsTracingIt) {
  testing::TempDir dir;
  auto scene = rich_scene(dir);
  const RayTracer tracer(*scene);
  const RenderResult base = render_with(*scene, tracer, nullptr, nullptr, true);
  const auto hook = std::make_shared<TiltHook>();
  const RenderResult traced = render_with(*scene, tracer, hook);
  ASSERT_TRUE(base.trace->keeps_shading());  // replayed from the shading records, not the rays
  const RenderResult replayed = render_with(*scene, tracer, hook, base.trace);
  expect_same_pixels(traced, replayed);
  EXPECT_EQ(replayed.gbuffer.object, traced.gbuffer.object);
  // Only samples beyond the base render's are traced.
  uint64_t beyond = 0;
  for (size_t p = 0; p < base.spp.size(); ++p)
    beyond += replayed.spp[p] > base.spp[p] ? replayed.spp[p] - base.spp[p] : 0;
  EXPECT_EQ(replayed.rays.primary, beyond);
  EXPECT_LT(replayed.rays.primary, traced.rays.primary / 4);
  EXPECT_NE(traced.radiance.pixels, base.radiance.pixels);  // the hook does change the image
}

TEST(TraceLog, AReplayedRenderWithATextureHookEqualsTracingIt) {
  testing::TempDir dir;
  auto scene = rich_scene(dir);
  const RayTracer tracer(*scene);
  const RenderResult base = render_with(*scene, tracer, nullptr, nullptr, true);
  auto texture = std::make_shared<HalfTexture>();
  texture->texture(0, scene->objects[0].material);
  RenderOptions options;
  options.threads = 2;
  options.texture_hook = texture;
  const RenderResult traced = render(*scene, tracer, options);
  options.replay_trace = base.trace;
  const RenderResult replayed = render(*scene, tracer, options);
  expect_same_pixels(traced, replayed);
  EXPECT_LT(replayed.rays.primary, traced.rays.primary / 4);
}

TEST(TraceLog, ALogOverItsLimitIsGivenUpAndTheImageStaysTheSame) {
  testing::TempDir dir;
  auto scene = rich_scene(dir);
  const RayTracer tracer(*scene);
  const RenderResult whole = render_with(*scene, tracer, nullptr, nullptr, true);
  uint64_t samples = 0;
  for (uint32_t n : whole.spp) samples += n;
  const uint64_t first_round = whole.trace->projected_bytes(48 * 36 * 4, false);  // min_spp 4
  const uint64_t all_rounds = whole.trace->projected_bytes(samples, false);
  ASSERT_GT(all_rounds, 2 * first_round);
  RenderOptions options;
  options.threads = 2;
  options.record_trace = true;
  options.trace_byte_limit = (first_round + all_rounds) / 2;  // fits the first round, not the last
  const RenderResult limited = render(*scene, tracer, options);
  EXPECT_EQ(limited.trace, nullptr);
  expect_same_pixels(whole, limited);
}

// A render that records its rays under a limit that fits them but not the shading records; the
// same image as the render that keeps its records (`whole`).
RenderResult render_without_records(const Scene& scene, const RayTracer& tracer,
                                    const RenderResult& whole) {
  uint64_t samples = 0;
  for (uint32_t n : whole.spp) samples += n;
  const uint64_t rays = whole.trace->projected_bytes(samples, false),
                 shading = whole.trace->projected_bytes(samples, true);
  EXPECT_LT(4 * rays, shading);  // the records are the bulk of the log
  RenderOptions options;
  options.threads = 2;
  options.record_trace = true;
  options.trace_byte_limit = 2 * rays;
  RenderResult limited = render(scene, tracer, options);
  expect_same_pixels(whole, limited);
  EXPECT_NE(limited.trace, nullptr);
  EXPECT_FALSE(limited.trace && limited.trace->keeps_shading());
  return limited;
}

TEST(TraceLog, ALogWhoseShadingRecordsDoNotFitKeepsItsRaysAndReplaysThem) {
  testing::TempDir dir;
  auto scene = rich_scene(dir);
  const RayTracer tracer(*scene);
  const RenderResult whole = render_with(*scene, tracer, nullptr, nullptr, true);
  ASSERT_TRUE(whole.trace->keeps_shading());
  const RenderResult limited = render_without_records(*scene, tracer, whole);
  ASSERT_NE(limited.trace, nullptr);
  const auto hook = std::make_shared<TiltHook>();
  const RenderResult replayed = render_with(*scene, tracer, hook, limited.trace);
  expect_same_pixels(render_with(*scene, tracer, hook), replayed);
  EXPECT_LT(replayed.rays.primary, whole.rays.primary / 4);
}

// A render that keeps its radiance only, at a fixed count, evaluates the log's records and does
// nothing else: the same pixels as tracing, no G-buffer, no ray.
TEST(TraceLog, ARadianceOnlyReplayAtAFixedCountEqualsTracingIt) {
  testing::TempDir dir;
  auto scene = fixed_count_scene(dir);
  const RayTracer tracer(*scene);
  const RenderResult base = render_with(*scene, tracer, nullptr, nullptr, true);
  ASSERT_TRUE(base.trace->keeps_shading());
  const auto hook = std::make_shared<TiltHook>();
  const RenderResult traced = render_with(*scene, tracer, hook);
  const RenderResult replayed = render_with(*scene, tracer, hook, base.trace, false, true);
  expect_same_pixels(traced, replayed);
  EXPECT_TRUE(replayed.gbuffer.object.empty());  // the records alone: no pass 1 either
  EXPECT_EQ(replayed.rays.primary + replayed.rays.shadow, 0u);
  EXPECT_NE(traced.radiance.pixels, base.radiance.pixels);
}

// Where the log cannot give every sample's record, a radiance-only render is a whole one.
TEST(TraceLog, ARadianceOnlyReplayWithoutRecordsRendersInFull) {
  testing::TempDir dir;
  auto scene = fixed_count_scene(dir);
  const RayTracer tracer(*scene);
  const RenderResult base =
      render_without_records(*scene, tracer, render_with(*scene, tracer, nullptr, nullptr, true));
  ASSERT_NE(base.trace, nullptr);
  const auto hook = std::make_shared<TiltHook>();
  const RenderResult replayed = render_with(*scene, tracer, hook, base.trace, false, true);
  expect_same_pixels(render_with(*scene, tracer, hook), replayed);
  EXPECT_FALSE(replayed.gbuffer.object.empty());
}

// Through the method interface: an extra λ of every method that renders again reads the base
// view's log and composes what it composes without one.
void every_method_composes_the_same(const std::shared_ptr<const Scene>& scene) {
  const std::vector<std::pair<std::string, nlohmann::json>> methods = {
      {"exaggerated-shading", {{"sigma", 0.1}}},
      {"lla", {{"sigma", 0.1}}},
      {"light-warping", nlohmann::json::object()},
      {"radiance-scaling", nlohmann::json::object()},
      {"texture-filter", {{"mode", "mip"}, {"filter", "unsharp"}, {"sigma", 1}}}};
  for (const auto& [method, parameters] : methods) {
    const auto view = render_view(scene, plan_for(method, parameters, 1.0), {8, 2, {}});
    ASSERT_NE(view->render.trace, nullptr) << method;
    auto untraced = std::make_shared<View>(*view);
    untraced->render.trace = nullptr;
    const auto with_log = prepare_method(method, view, parameters, 2);
    const auto without = prepare_method(method, untraced, parameters, 2);
    for (double lambda : {0.5, 1.0}) {
      const Image image = with_log->compose(lambda).display;
      EXPECT_EQ(image.pixels, without->compose(lambda).display.pixels)
          << method << " at " << lambda;
      EXPECT_NE(image.pixels, view->display.pixels)
          << method << " at " << lambda;  // the method does change it
    }
  }
}

TEST(TraceLog, EveryMethodThatRendersAgainComposesTheSameWithAndWithoutTheLog) {
  testing::TempDir dir;
  ::setenv("COUNTERSHADE_CACHE", (dir / "cache").c_str(), 1);  // texture-filter's pyramids
  // Adaptive sampling (the whole pixel pass replays) and a fixed count (the records alone).
  for (const auto& scene : {rich_scene(dir), fixed_count_scene(dir)})
    every_method_composes_the_same(scene);
}

}  // namespace
}  // namespace countershade
