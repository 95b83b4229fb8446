// What an extra λ costs for the methods that change shading, against the render they start from:
// the mestres2021 scene (igea, Lambertian, 512×384, 4 spp), both threads, with the light at 45°
// elevation towards the view (most of the face lit), and as a grazing side light (15°, 102.86°:
// most of the face on the light's dark side, which lla, exaggerated-shading and light-warping
// shade), without shadows as in the experiment and with them (each dark-side sample then traces a
// ray per λ).
//   build/bin/countershade_bench --benchmark_filter=ShadingExtraLambda
// The counter `vs_render` is (time of one compose at λ = 1) / (time of the render it starts from).
// TraceLogRecording: the render of that scene keeping its ray log (what a set does for these
// methods) against the same render without it; counter `vs_plain`.
// AlignLight: local light alignment (3 scales) of 64k random points one at a time (align_light)
// and in blocks of vector lanes (align_light_block), in one run; counter `block_vs_one` is the
// ratio of their times.

#include <benchmark/benchmark.h>

#include <chrono>
#include <glm/geometric.hpp>
#include <random>
#include <vector>

#include "enhance/light_alignment.h"
#include "enhance/method.h"
#include "enhance/view.h"
#include "extra_lambda.h"
#include "render/ray_tracer.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "stimuli/experiment.h"

namespace countershade {
namespace {

enum class Light { front, side, side_shadowed };

// igea under the experiment's light 8 (45°, 0°) or 3 (15°, 102.86°), the latter also with shadows.
std::shared_ptr<const Scene> mestres_scene(Light light) {
  static const Experiment e = load_experiment(std::string(COUNTERSHADE_SOURCE_DIR) +
                                              "/experiments/mestres2021/experiment.json");
  auto scene =
      std::make_shared<Scene>(load_experiment_scene(e, e.scenes[light == Light::front ? 7 : 2]));
  for (auto& l : scene->directional_lights) l.shadows = light == Light::side_shadowed;
  return scene;
}

void extra_lambda(benchmark::State& state, const std::string& method,
                  const nlohmann::json& parameters) {
  // The scene is loaded before any timing.
  measure_extra_lambda(state, mestres_scene(Light(state.range(0))), method, parameters);
}

void BM_ShadingExtraLambdaLla(benchmark::State& s) { extra_lambda(s, "lla", {{"sigma", 0.06}}); }
void BM_ShadingExtraLambdaEs(benchmark::State& s) {
  extra_lambda(s, "exaggerated-shading", {{"sigma", 0.06}});
}
void BM_ShadingExtraLambdaLw(benchmark::State& s) {
  extra_lambda(s, "light-warping", nlohmann::json::object());
}
void BM_ShadingExtraLambdaRs(benchmark::State& s) {
  extra_lambda(s, "radiance-scaling", nlohmann::json::object());
}
// Argument: 0 the front light, 1 the side light, 2 the side light with shadows.
BENCHMARK(BM_ShadingExtraLambdaLla)
    ->DenseRange(0, 2)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(3);
BENCHMARK(BM_ShadingExtraLambdaEs)
    ->DenseRange(0, 2)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(3);
BENCHMARK(BM_ShadingExtraLambdaLw)
    ->DenseRange(0, 2)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(3);
BENCHMARK(BM_ShadingExtraLambdaRs)
    ->DenseRange(0, 2)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(3);

double seconds_to_render(const Scene& scene, const RayTracer& tracer, bool record) {
  RenderOptions options;
  options.record_trace = record;
  const auto start = std::chrono::steady_clock::now();
  benchmark::DoNotOptimize(render(scene, tracer, options));
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BM_TraceLogRecording(benchmark::State& state) {
  const auto scene = mestres_scene(Light::front);
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

struct AlignmentPoints {
  std::vector<glm::dvec3> light, normals;  // normals: three per point, finest first
};

AlignmentPoints random_alignment_points(size_t count) {
  std::mt19937 random(3);
  std::normal_distribution<double> gauss;
  auto unit = [&](const glm::dvec3& around, double spread) {
    return glm::normalize(around +
                          spread * glm::dvec3(gauss(random), gauss(random), gauss(random)));
  };
  AlignmentPoints p;
  for (size_t k = 0; k < count; ++k) {
    const glm::dvec3 coarse = unit(glm::dvec3(0, 0, 1), 0.5), middle = unit(coarse, 0.3),
                     fine = unit(middle, 0.3);
    p.normals.insert(p.normals.end(), {fine, middle, coarse});
    p.light.push_back(unit(glm::dvec3(0.3, 0.2, 1), 0.5));
  }
  return p;
}

void BM_AlignLight(benchmark::State& state) {
  const size_t count = 65536;
  const AlignmentPoints p = random_alignment_points(count);
  const std::vector<double> strengths = {1.0, 1.0};
  const AlignmentWeight weight(3.0);
  AlignmentBlock block;
  double one = 0, blocks = 0, sum = 0;
  for (auto _ : state) {
    auto t = std::chrono::steady_clock::now();
    for (size_t k = 0; k < count; ++k)
      sum += align_light(p.light[k], {&p.normals[3 * k], 3}, strengths, weight).x;
    one += std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    t = std::chrono::steady_clock::now();
    for (size_t first = 0; first < count; first += kAlignmentBlock) {
      for (size_t j = 0; j < kAlignmentBlock; ++j)
        for (int c = 0; c < 3; ++c) {
          block.light[c][j] = p.light[first + j][c];
          for (int k = 0; k < 3; ++k)
            block.vectors[k][c][j] = p.normals[3 * (first + j) + size_t(k)][c];
        }
      align_light_block(block, kAlignmentBlock, 3, strengths, weight.damping());
      sum += block.aligned[0][0];
    }
    blocks += std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  }
  benchmark::DoNotOptimize(sum);
  const double n = double(state.iterations()) * double(count);
  state.counters["one_ns"] = 1e9 * one / n;
  state.counters["block_ns"] = 1e9 * blocks / n;
  state.counters["block_vs_one"] = blocks / one;
}
BENCHMARK(BM_AlignLight)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(20);

}  // namespace
}  // namespace countershade
