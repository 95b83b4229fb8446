// What an extra λ costs for the methods that change shading, against the render they start from:
// the mestres2021 scene (igea, Lambertian, 512×384, 4 spp, light at 45° elevation), both threads.
//   build/bin/countershade_bench --benchmark_filter=ShadingExtraLambda
// The counter `vs_render` is (time of one compose at λ = 1) / (time of the render it starts from).
// TraceLogRecording: the render of that scene keeping its ray log (what a set does for these
// methods) against the same render without it; counter `vs_plain`.

#include <benchmark/benchmark.h>

#include <chrono>

#include "extra_lambda.h"
#include "enhance/method.h"
#include "enhance/view.h"
#include "render/ray_tracer.h"
#include "render/renderer.h"
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

void extra_lambda(benchmark::State& state, const std::string& method, const nlohmann::json& parameters) {
  measure_extra_lambda(state, mestres_scene(), method, parameters);  // the scene is loaded before any timing
}

void BM_ShadingExtraLambdaLla(benchmark::State& s) { extra_lambda(s, "lla", {{"sigma", 0.06}}); }
void BM_ShadingExtraLambdaEs(benchmark::State& s) { extra_lambda(s, "exaggerated-shading", {{"sigma", 0.06}}); }
void BM_ShadingExtraLambdaLw(benchmark::State& s) { extra_lambda(s, "light-warping", nlohmann::json::object()); }
void BM_ShadingExtraLambdaRs(benchmark::State& s) { extra_lambda(s, "radiance-scaling", nlohmann::json::object()); }
BENCHMARK(BM_ShadingExtraLambdaLla)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_ShadingExtraLambdaEs)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_ShadingExtraLambdaLw)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(3);
BENCHMARK(BM_ShadingExtraLambdaRs)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(3);

double seconds_to_render(const Scene& scene, const RayTracer& tracer, bool record) {
  RenderOptions options;
  options.record_trace = record;
  const auto start = std::chrono::steady_clock::now();
  benchmark::DoNotOptimize(render(scene, tracer, options));
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BM_TraceLogRecording(benchmark::State& state) {
  const auto scene = mestres_scene();
  const RayTracer tracer(*scene);
  double plain = 0, recording = 0;
  for (auto _ : state) {
    plain += seconds_to_render(*scene, tracer, false);
    recording += seconds_to_render(*scene, tracer, true);
  }
  state.counters["plain_s"] = plain / double(state.iterations());
  state.counters["recording_s"] = recording / double(state.iterations());
  state.counters["vs_plain"] = recording / plain;
}
BENCHMARK(BM_TraceLogRecording)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(5);

}  // namespace
}  // namespace countershade
