// The per-λ part of a stimulus set at 1024×768 (lightness composition + PNG encoding + checksum)
// against rendering the scene, measured in one run.
//   build/bin/countershade_bench --benchmark_filter=Stimulus

#include <benchmark/benchmark.h>

#include <chrono>
#include <filesystem>

#include "core/sha256.h"
#include "enhance/view_plan.h"
#include "render/ray_tracer.h"
#include "render/scene_loader.h"
#include "stimuli/experiment.h"

namespace countershade {
namespace {

void BM_StimulusPerLambda(benchmark::State& state) {
  auto scene = std::make_shared<Scene>(load_scene(std::string(COUNTERSHADE_SOURCE_DIR) +
                                                  "/experiments/ritschel2008/scenes/chamfer.json"));
  auto t0 = std::chrono::steady_clock::now();
  const nlohmann::json parameters = {{"sigma_fraction", 0.02}};
  auto view = render_view(scene, plan_for("usm3d", parameters, 3.0), {});
  double render_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  auto prepared = prepare_method("usm3d", view, parameters);
  auto dir = std::filesystem::temp_directory_path() / "countershade-bench-stimuli";
  std::filesystem::create_directories(dir);
  double lambda = 0.05, per_image = 0, compose = 0;
  int images = 0;
  for (auto _ : state) {
    auto t1 = std::chrono::steady_clock::now();
    Composed c = prepared->compose(lambda);
    auto t2 = std::chrono::steady_clock::now();
    write_image(dir / "stimulus.png", c.display, {8});
    benchmark::DoNotOptimize(sha256_file(dir / "stimulus.png"));
    auto t3 = std::chrono::steady_clock::now();
    compose += std::chrono::duration<double>(t2 - t1).count();
    per_image += std::chrono::duration<double>(t3 - t1).count();
    lambda += 0.05;
    ++images;
  }
  std::filesystem::remove_all(dir);
  state.counters["render_s"] = render_seconds;
  state.counters["compose_ms"] = 1e3 * compose / images;
  state.counters["per_lambda_ms"] = 1e3 * per_image / images;
  state.counters["compose/render"] = compose / images / render_seconds;
}
BENCHMARK(BM_StimulusPerLambda)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(30);

}  // namespace
}  // namespace countershade
