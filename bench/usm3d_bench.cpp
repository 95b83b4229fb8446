// 3D unsharp masking costs on igea (134k vertices).
//   build/bin/countershade_bench --benchmark_filter='Smooth|Usm3d'

#include <benchmark/benchmark.h>

#include <chrono>
#include <cstring>
#include <numeric>

#include "core/random.h"
#include "enhance/method.h"
#include "enhance/usm3d.h"
#include "mesh/adjacency.h"
#include "mesh/mesh_io.h"
#include "mesh/smoothing.h"

namespace countershade {
namespace {

const std::string kSource = COUNTERSHADE_SOURCE_DIR;

const TriangleMesh& igea_mesh() {
  static TriangleMesh mesh = load_mesh(kSource + "/data/meshes/igea.obj");
  return mesh;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// n = 100 smoothing iterations at 1 and 2 threads; neighbour reads per second per core, and a
// STREAM-like copy of the same number of doubles measured in the same run for comparison.
void BM_SmoothIgea(benchmark::State& state) {
  const int threads = int(state.range(0));
  const TriangleMesh& mesh = igea_mesh();
  VertexAdjacency adj = adjacency_from_triangles(mesh.vertex_count(), mesh.triangles);
  Components comps = connected_components(adj);
  std::vector<int> iterations(comps.count, 100);
  std::vector<double> values(mesh.vertex_count());
  SampleStream random(1, 0, 0, 0);
  for (double& v : values) v = 100.0 * random.next();

  double smooth_seconds = 0, copy_seconds = 0;
  const size_t reads = adj.neighbours.size() * 100;
  std::vector<double> src(adj.neighbours.size(), 1.0), dst(adj.neighbours.size());
  for (auto _ : state) {
    auto t0 = std::chrono::steady_clock::now();
    laplacian_smooth(adj, comps.label, iterations, values, threads);
    smooth_seconds += seconds_since(t0);
    auto t1 = std::chrono::steady_clock::now();
    for (int i = 0; i < 100; ++i) {
      std::memcpy(dst.data(), src.data(), src.size() * sizeof(double));
      benchmark::ClobberMemory();
    }
    copy_seconds += seconds_since(t1);
  }
  double iterations_run = double(state.iterations());
  double smooth_rate = double(reads) * iterations_run / smooth_seconds;
  double copy_rate = double(reads) * iterations_run / copy_seconds;  // doubles copied per second (1 thread)
  state.counters["n100_ms"] = 1e3 * smooth_seconds / iterations_run;
  state.counters["reads/s/core"] = smooth_rate / threads;
  state.counters["copy/s"] = copy_rate;
  state.counters["reads/copy"] = smooth_rate / threads / copy_rate;
}
BENCHMARK(BM_SmoothIgea)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// n = 1000 steps on igea (2 threads), iterated and by the Chebyshev expansion, alternated in one
// run: the time of each and their ratio, and the largest difference relative to the range.
void BM_SmoothIgeaSchemes(benchmark::State& state) {
  const TriangleMesh& mesh = igea_mesh();
  const VertexAdjacency adj = adjacency_from_triangles(mesh.vertex_count(), mesh.triangles);
  const Components comps = connected_components(adj);
  const std::vector<int> steps(comps.count, 1000);
  std::vector<double> signal(mesh.vertex_count());
  SampleStream random(1, 0, 0, 0);
  for (double& v : signal) v = 100.0 * random.next();
  double seconds[2] = {0, 0}, largest = 0;
  for (auto _ : state) {
    std::vector<double> out[2] = {signal, signal};
    for (int scheme = 0; scheme < 2; ++scheme) {
      auto t0 = std::chrono::steady_clock::now();
      smooth_over_rings(adj, comps.label, steps, out[scheme], scheme ? SmoothingScheme::chebyshev : SmoothingScheme::iterate, 2);
      seconds[scheme] += seconds_since(t0);
    }
    for (size_t v = 0; v < signal.size(); ++v) largest = std::max(largest, std::abs(out[0][v] - out[1][v]) / 100.0);
  }
  const double runs = double(state.iterations());
  state.counters["iterate_ms"] = 1e3 * seconds[0] / runs;
  state.counters["chebyshev_ms"] = 1e3 * seconds[1] / runs;
  state.counters["speedup"] = seconds[0] / seconds[1];
  state.counters["max_diff/range"] = largest;
}
BENCHMARK(BM_SmoothIgeaSchemes)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

// igea under the sky at 1024×768 with a fixed 16 spp (4 per vertex point), so both renders take
// the same samples.
std::shared_ptr<const Scene> igea_scene() {
  static std::shared_ptr<const Scene> scene = [] {
    auto s = std::make_shared<Scene>(load_scene(kSource + "/experiments/scenes/igea-sky.json"));
    s->settings.spp = 16;
    return s;
  }();
  return scene;
}

// Plain render against render + vertex signal + smoothing + one composition, 1024×768, 16 spp,
// one σ with n ≈ 50; both measured in the same run. Arg: 1-ring samples per triangle (0 = off).
void BM_Usm3dOverhead(benchmark::State& state) {
  auto scene = igea_scene();
  const int ring = int(state.range(0));
  const double h = mean_edge_length(scene->objects[0].mesh);
  const nlohmann::json options = {{"sigma", std::sqrt(50.0 / 2.0) * h}, {"ring_samples", ring}};  // n = round(2σ²/h̄²) ≈ 50
  double plain = 0, enhanced = 0, extra_lambda = 0;
  int n = 0;
  for (auto _ : state) {
    auto t0 = std::chrono::steady_clock::now();
    Composed none = prepare_method("none", render_view(scene), nlohmann::json::object())->compose(0);
    plain += seconds_since(t0);
    benchmark::DoNotOptimize(none.display.pixels.data());

    auto t1 = std::chrono::steady_clock::now();
    auto view = render_view(scene, plan_for("usm3d", options, 1.0), {});
    auto prepared = prepare_method("usm3d", view, options);
    Composed out = prepared->compose(1.0);
    enhanced += seconds_since(t1);
    n = prepared->parameters()["iterations"]["igea"].get<int>();

    auto t2 = std::chrono::steady_clock::now();
    Composed more = prepared->compose(2.0);
    extra_lambda += seconds_since(t2);
    benchmark::DoNotOptimize(more.display.pixels.data());
  }
  double runs = double(state.iterations());
  state.counters["plain_s"] = plain / runs;
  state.counters["usm3d_s"] = enhanced / runs;
  state.counters["overhead"] = enhanced / plain - 1.0;
  state.counters["extra_lambda_ms"] = 1e3 * extra_lambda / runs;
  state.counters["extra_lambda/render"] = extra_lambda / plain;
  state.counters["n"] = n;
}
BENCHMARK(BM_Usm3dOverhead)->Arg(0)->Arg(3)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace
}  // namespace countershade
