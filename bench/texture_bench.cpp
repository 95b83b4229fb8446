// Mip-mapped textures and texture-space filtering (docs/performance.md):
//   build/bin/countershade_bench --benchmark_filter='Texture'
// - TexturePyramidBuild: the box-filtered pyramid of a 2048² texture.
// - TextureFilterPyramid/{unsharp,bilateral,dog}: one filter over every level of that pyramid
//   (mip mode, σ = 2 texels, no cache): the work done once per (texture, filter, σ).
// - TextureLookup{Single,Trilinear}: one lookup at random UVs, level 0 bilinear against trilinear
//   with a square footprint of 2.83 texels (level 1.5, one probe); their ratio is the cost of
//   mip-mapping a lookup.
// - TextureFilterExtraLambda: one λ of texture-filter in mip mode on the semmo2015 ground
//   (512×384): the filtered pyramid at that λ plus the render with it, against the plain render
//   (counter vs_render).

#include <benchmark/benchmark.h>

#include <random>

#include "enhance/filtered_pyramid.h"
#include "enhance/method.h"
#include "enhance/view.h"
#include "extra_lambda.h"
#include "render/procedural_texture.h"
#include "stimuli/experiment.h"

namespace countershade {
namespace {

const TextureLevel& texture_2048() {
  static const TextureLevel level = checker_noise({2048, 32, 0.35, 1});
  return level;
}

void BM_TexturePyramidBuild(benchmark::State& state) {
  const TextureLevel& base = texture_2048();  // made before the timing
  for (auto _ : state) benchmark::DoNotOptimize(Texture(base));
}
BENCHMARK(BM_TexturePyramidBuild)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_TextureFilterPyramid(benchmark::State& state) {
  const auto plain = std::make_shared<const Texture>(texture_2048());
  LightnessFilter f;
  f.kind = FilterKind(state.range(0));
  state.SetLabel(filter_name(f.kind));
  for (auto _ : state)
    benchmark::DoNotOptimize(filter_pyramid(plain, TextureMode::mip, f, {}, std::nullopt));
}
BENCHMARK(BM_TextureFilterPyramid)
    ->DenseRange(0, 2)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

void lookups(benchmark::State& state, double footprint) {
  static const Texture texture(texture_2048());
  std::mt19937_64 random(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<glm::dvec2> uvs(4096);
  for (auto& uv : uvs) uv = {u(random), u(random)};
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        texture.sample(uvs[i], glm::dvec2(footprint, 0.0), glm::dvec2(0.0, footprint)));
    i = (i + 1) & 4095;
  }
}
void BM_TextureLookupSingle(benchmark::State& s) { lookups(s, 0.0); }
void BM_TextureLookupTrilinear(benchmark::State& s) { lookups(s, 2.83 / 2048); }
BENCHMARK(BM_TextureLookupSingle);
BENCHMARK(BM_TextureLookupTrilinear);

void BM_TextureFilterExtraLambda(benchmark::State& state) {
  const Experiment e = load_experiment(std::string(COUNTERSHADE_SOURCE_DIR) +
                                       "/experiments/semmo2015/experiment.json");
  const auto scene = std::make_shared<const Scene>(load_experiment_scene(e, e.scenes[0]));
  measure_extra_lambda(state, scene, "texture-filter",
                       {{"mode", "mip"}, {"filter", "unsharp"}, {"sigma", 1}});
}
BENCHMARK(BM_TextureFilterExtraLambda)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(3);

}  // namespace
}  // namespace countershade
