// The noise budget's sampling (Owen-scrambled Sobol, adaptive per pixel and per vertex) against
// independent random numbers at a fixed count, at equal time, on the scan scene of the
// ritschel2008 set (usm3d, λ = 3, σ = 0.12, 512×384):
//   build/bin/countershade_bench --benchmark_filter=EqualTime
// The independent count is calibrated so that its render takes as long as the budget's. Noise is
// measured as an observer meets it: the L* difference of the written 8-bit stimuli of two seeds,
// over √2.

#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>

#include "core/display.h"
#include "core/image.h"
#include "enhance/lightness.h"
#include "enhance/registry.h"
#include "enhance/view.h"
#include "enhance/view_plan.h"
#include "render/scene.h"
#include "render/scene_loader.h"

namespace countershade {
namespace {

const nlohmann::json kUsm3d = {{"sigma", 0.12}, {"ring_samples", 3}};

Scene scan_scene() {
  // A path, not a std::string sum: GCC 12 falsely warns of an out-of-bounds copy in the latter.
  Scene s = load_scene(std::filesystem::path(COUNTERSHADE_SOURCE_DIR) /
                       "experiments/ritschel2008/scenes/scan.json");
  s.camera.width = 512;
  s.camera.height = 384;
  return s;
}

struct Stimulus {
  std::vector<float> lightness;  // L* of the written 8-bit image
  double seconds = 0;            // render and preparation
  double mean_spp = 0;
};

Stimulus render_stimulus(Scene scene, uint64_t seed) {
  scene.settings.seed = seed;
  const auto t0 = std::chrono::steady_clock::now();
  auto view = render_view(std::make_shared<Scene>(std::move(scene)), plan_for("usm3d", kUsm3d, 3.0),
                          ViewOptions{});
  Image display = prepare_method("usm3d", view, kUsm3d)->compose(3.0).display;
  Stimulus out;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.mean_spp = view->render.sampling.pixels.mean;
  for (float& v : display.pixels) v = float(quantize(v, 8)) / 255.0f;
  const DisplayEncoding srgb = DisplayEncoding::srgb();
  for (size_t p = 0; p < display.pixels.size() / 3; ++p)
    out.lightness.push_back(float(display_pixel_to_lab(&display.pixels[3 * p], srgb).L));
  return out;
}

double two_seed_rms(const Stimulus& a, const Stimulus& b) {
  double sum = 0;
  for (size_t p = 0; p < a.lightness.size(); ++p) {
    const double d = double(a.lightness[p]) - b.lightness[p];
    sum += d * d / 2.0;
  }
  return std::sqrt(sum / double(a.lightness.size()));
}

Scene independent(Scene scene, int spp) {
  scene.settings.sampling = SamplingMode::independent;
  scene.settings.spp = spp;
  return scene;
}

void BM_NoiseAtEqualTime(benchmark::State& state) {
  for (auto _ : state) {
    const Scene budget = scan_scene();
    const Stimulus a = render_stimulus(budget, 1), b = render_stimulus(budget, 2);
    const double budget_seconds = 0.5 * (a.seconds + b.seconds);
    // Calibrate: the independent sampler's time per sample per pixel, from a 16-spp render.
    const Stimulus probe = render_stimulus(independent(budget, 16), 3);
    const int spp = std::max(2, 2 * int(std::lround(0.5 * 16.0 * budget_seconds / probe.seconds)));
    const Stimulus c = render_stimulus(independent(budget, spp), 1),
                   d = render_stimulus(independent(budget, spp), 2);
    const double budget_rms = two_seed_rms(a, b), independent_rms = two_seed_rms(c, d);
    state.counters["budget_s"] = budget_seconds;
    state.counters["budget_mean_spp"] = a.mean_spp;
    state.counters["budget_Lrms"] = budget_rms;
    state.counters["independent_s"] = 0.5 * (c.seconds + d.seconds);
    state.counters["independent_spp"] = spp;
    state.counters["independent_Lrms"] = independent_rms;
    state.counters["noise_ratio"] = independent_rms / budget_rms;
    state.counters["time_ratio"] = 0.5 * (c.seconds + d.seconds) / budget_seconds;
  }
}
BENCHMARK(BM_NoiseAtEqualTime)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace
}  // namespace countershade
