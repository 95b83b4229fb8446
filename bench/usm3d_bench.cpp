// 3D unsharp masking costs on igea (134k vertices).
//   build/bin/countershade_bench --benchmark_filter='Smooth|Usm3d'

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <numeric>
#include <random>

#include "core/random.h"
#include "enhance/method.h"
#include "enhance/usm3d.h"
#include "enhance/view_plan.h"
#include "face_scatter_smoothing.h"
#include "mesh/adjacency.h"
#include "mesh/mesh_io.h"
#include "mesh/smoothing.h"
#include "mesh/vertex_order.h"
#include "render/scene_loader.h"
#include "subdivided_mesh.h"

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
  double copy_rate =
      double(reads) * iterations_run / copy_seconds;  // doubles copied per second (1 thread)
  state.counters["n100_ms"] = 1e3 * smooth_seconds / iterations_run;
  state.counters["reads/s/core"] = smooth_rate / threads;
  state.counters["copy/s"] = copy_rate;
  state.counters["reads/copy"] = smooth_rate / threads / copy_rate;
}
BENCHMARK(BM_SmoothIgea)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// `count` random 8-bit levels (a fixed stream).
std::vector<uint8_t> random_levels(size_t count) {
  std::vector<uint8_t> grey(count);
  SampleStream random(1, 0, 0, 0);
  for (uint8_t& g : grey) g = uint8_t(255.0 * random.next());
  return grey;
}

// igea's 1-ring graph with n = 1000 steps for its components, and a random signal of 8-bit levels.
struct IgeaSmoothing {
  VertexAdjacency adj = adjacency_from_triangles(igea_mesh().vertex_count(), igea_mesh().triangles);
  Components comps = connected_components(adj);
  std::vector<int> steps = std::vector<int>(comps.count, 1000);
  std::vector<uint8_t> grey = random_levels(igea_mesh().vertex_count());
  std::vector<double> signal = std::vector<double>(grey.begin(), grey.end());
};

// n = 1000 steps on igea (2 threads), iterated and by the Chebyshev expansion, alternated in one
// run: the time of each and their ratio, and the largest difference relative to the range.
void BM_SmoothIgeaSchemes(benchmark::State& state) {
  const auto [adj, comps, steps, grey, signal] = IgeaSmoothing();
  double seconds[2] = {0, 0}, largest = 0;
  for (auto _ : state) {
    std::vector<double> out[2] = {signal, signal};
    for (int scheme = 0; scheme < 2; ++scheme) {
      auto t0 = std::chrono::steady_clock::now();
      smooth_over_rings(adj, comps.label, steps, out[scheme],
                        scheme ? SmoothingScheme::chebyshev : SmoothingScheme::iterate, 2);
      seconds[scheme] += seconds_since(t0);
    }
    for (size_t v = 0; v < signal.size(); ++v)
      largest = std::max(largest, std::abs(out[0][v] - out[1][v]) / 255.0);
  }
  const double runs = double(state.iterations());
  state.counters["iterate_ms"] = 1e3 * seconds[0] / runs;
  state.counters["chebyshev_ms"] = 1e3 * seconds[1] / runs;
  state.counters["speedup"] = seconds[0] / seconds[1];
  state.counters["max_diff/range"] = largest;
}
BENCHMARK(BM_SmoothIgeaSchemes)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

// n = 1000 steps on igea against the face-scatter baseline of vcglib's algorithm
// (bench/face_scatter_smoothing.h, serial), each scheme at 1 and at 2 threads, one after another
// in each run. How many times faster than the baseline each is.
void BM_SmoothAgainstFaceScatter(benchmark::State& state) {
  const TriangleMesh& mesh = igea_mesh();
  const auto [adj, comps, steps, grey, signal] = IgeaSmoothing();
  double baseline = 0, ours[2][2] = {{0, 0}, {0, 0}};  // [scheme][threads − 1]
  for (auto _ : state) {
    bench::FaceScatterMesh m = bench::face_scatter_mesh(mesh, grey);
    auto t0 = std::chrono::steady_clock::now();
    bench::face_scatter_smooth(m, 1000);
    baseline += seconds_since(t0);
    benchmark::DoNotOptimize(m.vertices.data());
    for (int scheme = 0; scheme < 2; ++scheme)
      for (int threads = 1; threads <= 2; ++threads) {
        std::vector<double> out = signal;
        auto t1 = std::chrono::steady_clock::now();
        smooth_over_rings(adj, comps.label, steps, out,
                          scheme ? SmoothingScheme::chebyshev : SmoothingScheme::iterate, threads);
        ours[scheme][threads - 1] += seconds_since(t1);
      }
  }
  const double runs = double(state.iterations());
  state.counters["face_scatter_ms"] = 1e3 * baseline / runs;
  const char* names[2][2] = {{"x_iterate_1t", "x_iterate_2t"},
                             {"x_chebyshev_1t", "x_chebyshev_2t"}};
  for (int scheme = 0; scheme < 2; ++scheme)
    for (int t = 0; t < 2; ++t) state.counters[names[scheme][t]] = baseline / ours[scheme][t];
}
BENCHMARK(BM_SmoothAgainstFaceScatter)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(2);

// The share of ring entries more than 8192 indices from their vertex.
double far_share(const VertexAdjacency& adj) {
  size_t far = 0;
  for (uint32_t v = 0; v < adj.vertex_count(); ++v)
    for (uint32_t w : adj.of(v)) far += (v > w ? v - w : w - v) > 8192;
  return double(far) / double(adj.neighbours.size());
}

// Locality (mesh/vertex_order.h): n = 100 iterated steps at 2 threads on igea cut into 9 triangles
// each (1.2 M vertices, bench/subdivided_mesh.h), in three vertex orders: the file's, a random
// shuffle (the worst a scan's order can be) and breadth first. Nanoseconds per vertex per step.
// Arg 0: the subdivision's order, 1: shuffled; each run smooths the order as given and then
// through smooth_over_rings, which renumbers (its time includes the renumbering).
void BM_SmoothLocality(benchmark::State& state) {
  static const bench::Subdivided fine = bench::subdivide(igea_mesh(), 3);
  std::vector<uint32_t> order(fine.positions.size());
  std::iota(order.begin(), order.end(), 0u);
  if (state.range(0) == 1) std::shuffle(order.begin(), order.end(), std::mt19937(1));
  const VertexAdjacency adj =
      renumbered(adjacency_from_triangles(order.size(), fine.triangles), order);
  const Components comps = connected_components(adj);
  const std::vector<int> steps(comps.count, 100);
  const std::vector<uint8_t> grey = random_levels(order.size());
  const std::vector<double> signal(grey.begin(), grey.end());
  double seconds[2] = {0, 0};
  bool same = true;
  for (auto _ : state) {
    std::vector<double> out[2] = {signal, signal};
    auto t0 = std::chrono::steady_clock::now();
    laplacian_smooth(adj, comps.label, steps, out[0], 2);
    seconds[0] += seconds_since(t0);
    auto t1 = std::chrono::steady_clock::now();
    smooth_over_rings(adj, comps.label, steps, out[1], SmoothingScheme::iterate, 2);
    seconds[1] += seconds_since(t1);
    same = same && out[0] == out[1];
  }
  const double per_step = 1e9 / (double(state.iterations()) * 100.0 * double(order.size()));
  const auto t2 = std::chrono::steady_clock::now();
  const VertexAdjacency local = renumbered(adj, breadth_first_order(adj));
  state.counters["renumber_ms"] = 1e3 * seconds_since(t2);
  state.counters["far_given"] = far_share(adj);
  state.counters["far_breadth_first"] = far_share(local);
  state.counters["as_given_ns"] = seconds[0] * per_step;
  state.counters["breadth_first_ns"] = seconds[1] * per_step;
  state.counters["speedup"] = seconds[0] / seconds[1];
  state.counters["same_bits"] = same;
}
BENCHMARK(BM_SmoothLocality)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(2);

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
  const nlohmann::json options = {{"sigma", std::sqrt(50.0 / 2.0) * h},
                                  {"ring_samples", ring}};  // n = round(2σ²/h̄²) ≈ 50
  double plain = 0, enhanced = 0, extra_lambda = 0;
  int n = 0;
  for (auto _ : state) {
    auto t0 = std::chrono::steady_clock::now();
    Composed none =
        prepare_method("none", render_view(scene), nlohmann::json::object())->compose(0);
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
