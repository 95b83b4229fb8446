// One further λ of every lightness method at 1920×1080: the lightness-only composition alone,
// after the once-per-σ preparation.
//   build/bin/countershade_bench --benchmark_filter=ComposeLightness

#include <benchmark/benchmark.h>

#include "core/isa.h"
#include "enhance/lightness.h"
#include "enhance/method.h"
#include "enhance/view_plan.h"
#include "render/scene_loader.h"

namespace countershade {
namespace {

constexpr int kWidth = 1920, kHeight = 1080;

struct Case {
  const char* method;
  nlohmann::json parameters;
};

const Case kCases[] = {
    {"usm3d", {{"sigma_fraction", 0.05}}},
    {"usm2d", {{"sigma_percent", 1.0}}},
    {"cornsweet", {{"sigma_px", 16}}},
    {"depth-usm", {{"operator", "darken"}, {"space", "lab"}, {"kernel_percent", 5}}},
    {"depth-usm", {{"operator", "contrast"}, {"space", "lab"}, {"kernel_percent", 5}}},
};

// The Cornsweet cube at 1920×1080, one sample per pixel (the composition does not care),
// rendered for every case.
std::shared_ptr<const View> rendered_view() {
  static std::shared_ptr<const View> view = [] {
    auto scene = std::make_shared<Scene>(load_scene(std::string(COUNTERSHADE_SOURCE_DIR) +
                                                    "/experiments/scenes/cornsweet-cube.json"));
    scene->camera.width = kWidth;
    scene->camera.height = kHeight;
    scene->settings.spp = 1;
    scene->settings.vertex_spp = 4;
    ViewPlan plan;
    plan.max_abs_lambda = 3;
    for (const Case& c : kCases) plan.add(c.method, c.parameters);
    return render_view(scene, plan, {});
  }();
  return view;
}

void BM_ComposeLightness(benchmark::State& state) {
  const Case& c = kCases[state.range(0)];
  auto prepared = prepare_method(c.method, rendered_view(), c.parameters);
  allow_avx512(state.range(1) != 0);
  double lambda = 0.5;
  for (auto _ : state) {
    Composed out = prepared->compose(lambda);
    benchmark::DoNotOptimize(out.display.pixels.data());
    lambda += 0.01;
  }
  allow_avx512(true);
  state.SetLabel(std::string(c.method) + " " + c.parameters.dump() +
                 (state.range(1) ? "" : ", four pixels at a time"));
}
// The second argument: 1 lets the composition take eight pixels at a time where the processor has
// AVX-512 (the default), 0 keeps it at four (the path of other processors), for an A/B in one run.
BENCHMARK(BM_ComposeLightness)
    ->ArgsProduct({benchmark::CreateDenseRange(0, 4, 1), {1, 0}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace countershade
