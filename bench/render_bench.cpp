// Ray throughput of the Embree renderer on the bunny scene at 1024×768, the renderer's pace
// against Embree's own on the same rays, and loading scenes.
//   build/bin/countershade_bench --benchmark_filter=Rays
//   build/bin/countershade_bench --benchmark_filter=RayRatio
//   build/bin/countershade_bench --benchmark_filter=LoadScene

#include <benchmark/benchmark.h>

#include <chrono>
#include <glm/geometric.hpp>

#include "core/parallel.h"
#include "core/random.h"
#include "render/ray_recorder.h"
#include "render/ray_tracer.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "render/scene_loader.h"
#include "render/shading.h"

namespace countershade {
namespace {

const Scene& bunny_scene() {
  static Scene scene = [] {
    Scene s =
        load_scene(std::string(COUNTERSHADE_SOURCE_DIR) + "/experiments/scenes/bunny-sky.json");
    s.camera.width = 1024;
    s.camera.height = 768;
    return s;
  }();
  return scene;
}

const RayTracer& bunny_tracer() {
  static RayTracer tracer(bunny_scene());
  return tracer;
}

// Primary rays: one through every pixel centre, single-threaded.
void BM_PrimaryRays(benchmark::State& state) {
  const Scene& scene = bunny_scene();
  const RayTracer& tracer = bunny_tracer();
  CameraRays rays(scene.camera);
  int64_t count = 0, hits = 0;
  for (auto _ : state) {
    for (int y = 0; y < scene.camera.height; ++y)
      for (int x = 0; x < scene.camera.width; ++x) {
        Ray r = rays.ray(x + 0.5, y + 0.5);
        hits += tracer.intersect(r.origin, r.direction).has_value();
      }
    count += int64_t(scene.camera.width) * scene.camera.height;
  }
  benchmark::DoNotOptimize(hits);
  state.counters["rays/s"] = benchmark::Counter(double(count), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PrimaryRays)->Unit(benchmark::kMillisecond)->UseRealTime();

// Shadow rays: from every visible surface point towards cosine-distributed sky directions,
// single-threaded (the environment light's visibility rays).
void BM_ShadowRays(benchmark::State& state) {
  const Scene& scene = bunny_scene();
  const RayTracer& tracer = bunny_tracer();
  CameraRays rays(scene.camera);
  std::vector<std::pair<glm::dvec3, glm::dvec3>> points;  // position, normal
  for (int y = 0; y < scene.camera.height; ++y)
    for (int x = 0; x < scene.camera.width; ++x) {
      Ray r = rays.ray(x + 0.5, y + 0.5);
      if (auto hit = tracer.intersect(r.origin, r.direction)) {
        SurfacePoint sp = surface_point(scene, hit->object, hit->triangle, hit->b1, hit->b2);
        points.emplace_back(sp.position, sp.geometric_normal);
      }
    }
  int64_t count = 0, blocked = 0;
  uint64_t i = 0;
  for (auto _ : state) {
    for (const auto& [p, n] : points) {
      SampleStream random(1, kDomainPixel, i++, 0);
      glm::dvec3 d = sample_cosine_hemisphere(TangentFrame(n), random.next(), random.next());
      blocked += tracer.occluded(p + n * tracer.epsilon(), d, tracer.epsilon(), 1e30);
    }
    count += int64_t(points.size());
  }
  benchmark::DoNotOptimize(blocked);
  state.counters["rays/s"] = benchmark::Counter(double(count), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ShadowRays)->Unit(benchmark::kMillisecond)->UseRealTime();

// The whole render (16 spp, 12 environment samples each) on all cores, with its ray mix.
void BM_RenderBunny(benchmark::State& state) {
  Scene scene = bunny_scene();
  scene.settings.spp = int(state.range(0));
  const RayTracer& tracer = bunny_tracer();
  RayCounts total;
  for (auto _ : state) total += render(scene, tracer).rays;
  state.counters["primary/s"] =
      benchmark::Counter(double(total.primary), benchmark::Counter::kIsRate);
  state.counters["shadow/s"] =
      benchmark::Counter(double(total.shadow), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RenderBunny)->Arg(4)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

void BM_BuildBvh(benchmark::State& state) {
  const Scene& scene = bunny_scene();
  for (auto _ : state) {
    RayTracer tracer(scene);
    benchmark::DoNotOptimize(tracer.epsilon());
  }
}
BENCHMARK(BM_BuildBvh)->Unit(benchmark::kMillisecond)->UseRealTime();

// Loading a scene with its surface graphs (as usm3d loads it) on 1 or 2 threads: the objects' mesh
// files load in parallel, and each graph is built while the next object is read.
void BM_LoadScene(benchmark::State& state) {
  const char* const names[] = {"bunny-sky", "igea-sky", "clutter"};
  const std::string name = names[state.range(0)];
  const std::string file =
      std::string(COUNTERSHADE_SOURCE_DIR) + "/experiments/scenes/" + name + ".json";
  for (auto _ : state)
    run_with_threads(int(state.range(1)),
                     [&] { benchmark::DoNotOptimize(load_scene(file, true).objects.size()); });
  state.SetLabel(name + ", " + std::to_string(state.range(1)) + " thread(s)");
}
BENCHMARK(BM_LoadScene)
    ->ArgsProduct({{0, 1, 2}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The renderer's pace against Embree's own on the same rays: a render at a fixed count (4 samples
// per pixel, 512×384, one thread), timed without a recorder and recorded in a second run (the same
// rays: renders are deterministic), then the recorded rays traced through Embree alone, one at a
// time, in their order. The timed render is the scene's second, as every render of a stimulus set
// but its first: the first one's buffers stay in the heap (core/allocator.h), and the second does
// not fault their pages in again. The ratio is the renderer's rays per second over Embree's: the
// share of a render's time that is Embree's. The render's time is also given in two parts, with
// Embree's.
void BM_RayRatio(benchmark::State& state) {
  const char* const files[] = {"experiments/scenes/bunny-sky.json",
                               "experiments/ritschel2008/scenes/chamfer.json"};
  Scene scene = load_scene(std::string(COUNTERSHADE_SOURCE_DIR) + "/" + files[state.range(0)]);
  scene.camera.width = 512;
  scene.camera.height = 384;
  scene.settings.spp = 4;
  RayTracer tracer(scene);
  RayRecorder recorder;
  double render_seconds = 0, replay_seconds = 0, pixel_seconds = 0;
  size_t rays = 0;
  for (auto _ : state)
    run_with_threads(1, [&] {
      render(scene, tracer);  // a render first, so that the timed one finds its memory in the heap
      const auto t0 = std::chrono::steady_clock::now();
      pixel_seconds += render(scene, tracer).sampling.seconds;
      const auto t1 = std::chrono::steady_clock::now();
      tracer.record_rays(&recorder);
      render(scene, tracer);
      tracer.record_rays(nullptr);
      const std::vector<RecordedRay> recorded = recorder.take();
      const auto t2 = std::chrono::steady_clock::now();
      benchmark::DoNotOptimize(tracer.replay(recorded));
      const auto t3 = std::chrono::steady_clock::now();
      render_seconds += std::chrono::duration<double>(t1 - t0).count();
      replay_seconds += std::chrono::duration<double>(t3 - t2).count();
      rays += recorded.size();
    });
  state.counters["rays"] = double(rays) / double(state.iterations());
  state.counters["renderer Mrays/s"] = double(rays) / render_seconds / 1e6;
  state.counters["Embree Mrays/s"] = double(rays) / replay_seconds / 1e6;
  state.counters["ratio"] = replay_seconds / render_seconds;
  // Where the render's time goes: its pixel pass (the samples' shading, shadow rays and sums), and
  // the rest (the G-buffer, the camera samples traced ahead, the image made from the sums).
  state.counters["pixel pass s"] = pixel_seconds / double(state.iterations());
  state.counters["rest s"] = (render_seconds - pixel_seconds) / double(state.iterations());
  state.counters["Embree alone s"] = replay_seconds / double(state.iterations());
  state.SetLabel(state.range(0) == 0 ? "bunny-sky" : "chamfer");
}
BENCHMARK(BM_RayRatio)->Arg(0)->Arg(1)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace
}  // namespace countershade
