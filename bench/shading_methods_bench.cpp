// What an extra λ costs for the methods that change shading, against the render they start from:
// the mestres2021 scene (igea, Lambertian, 512×384, 4 spp, light at 45° elevation), both threads.
//   build/bin/countershade_bench --benchmark_filter=ShadingExtraLambda
// The counter `vs_render` is (time of one compose at λ = 1) / (time of the plain render).

#include <benchmark/benchmark.h>

#include <chrono>

#include "enhance/method.h"
#include "enhance/view.h"
#include "render/scene.h"
#include "stimuli/experiment.h"

namespace countershade {
namespace {

std::shared_ptr<const Scene> mestres_scene() {
  static std::shared_ptr<const Scene> scene = [] {
    const Experiment e = load_experiment(std::string(COUNTERSHADE_SOURCE_DIR) + "/experiments/mestres2021/experiment.json");
    return std::make_shared<const Scene>(load_experiment_scene(e, e.scenes[7]));  // igea-e45-a0
  }();
  return scene;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

void extra_lambda(benchmark::State& state, const std::string& method, const nlohmann::json& parameters) {
  double render = 0, compose = 0;
  const std::shared_ptr<const Scene> scene = mestres_scene();  // loaded before any timing
  for (auto _ : state) {
    auto t = std::chrono::steady_clock::now();
    const auto view = render_view(scene);
    render += seconds_since(t);
    const auto prepared = prepare_method(method, view, parameters);
    t = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(prepared->compose(1.0));
    compose += seconds_since(t);
  }
  state.counters["render_s"] = render / double(state.iterations());
  state.counters["compose_s"] = compose / double(state.iterations());
  state.counters["vs_render"] = compose / render;
}

void BM_ShadingExtraLambdaLla(benchmark::State& s) { extra_lambda(s, "lla", {{"sigma", 0.06}}); }
void BM_ShadingExtraLambdaEs(benchmark::State& s) { extra_lambda(s, "exaggerated-shading", {{"sigma", 0.06}}); }
void BM_ShadingExtraLambdaLw(benchmark::State& s) { extra_lambda(s, "light-warping", nlohmann::json::object()); }
void BM_ShadingExtraLambdaRs(benchmark::State& s) { extra_lambda(s, "radiance-scaling", nlohmann::json::object()); }
BENCHMARK(BM_ShadingExtraLambdaLla)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_ShadingExtraLambdaEs)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_ShadingExtraLambdaLw)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_ShadingExtraLambdaRs)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(3);

}  // namespace
}  // namespace countershade
