// Image-space methods at 1920×1080: depth-buffer unsharp masking (K = 1% and 5% of the diagonal in
// one run) and 2D unsharp masking against OpenImageIO's unsharp_mask on the same image.
//   build/bin/countershade_bench --benchmark_filter='DepthUsm|Usm2d'

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/gaussian.h"
#include "core/random.h"
#include "enhance/depth_usm.h"
#include "enhance/image_width.h"
#include "enhance/lightness.h"
#include "enhance/method.h"
#include "enhance/view.h"
#include "enhance/view_plan.h"
#include "render/scene_loader.h"

namespace countershade {
namespace {

constexpr int kWidth = 1920, kHeight = 1080;

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + long(v.size() / 2), v.end());
  return v[v.size() / 2];
}

// Seconds since `start`, appended to `times`; returns now.
std::chrono::steady_clock::time_point lap(std::chrono::steady_clock::time_point start,
                                          std::vector<double>& times) {
  const auto now = std::chrono::steady_clock::now();
  times.push_back(std::chrono::duration<double>(now - start).count());
  return now;
}

// A synthetic stimulus: textured noise and overlapping discs at different depths on a far wall.
const std::shared_ptr<const View>& test_view() {
  static std::shared_ptr<const View> view = [] {
    Image display(kWidth, kHeight, 3);
    std::vector<float> depth(size_t(kWidth) * kHeight, 10.0f);
    SampleStream random(7, 0, 0, 0);
    for (size_t i = 0; i < depth.size(); ++i)
      for (int c = 0; c < 3; ++c) display.pixels[3 * i + c] = 0.35f + 0.1f * float(random.next());
    for (int disc = 0; disc < 40; ++disc) {
      double cx = random.next() * kWidth, cy = random.next() * kHeight,
             r = 40 + 160 * random.next();
      float z = float(2.0 + 7.0 * random.next()), grey = float(0.2 + 0.6 * random.next());
      for (int y = std::max(0, int(cy - r)); y < std::min(kHeight, int(cy + r)); ++y)
        for (int x = std::max(0, int(cx - r)); x < std::min(kWidth, int(cx + r)); ++x) {
          size_t i = size_t(y) * kWidth + x;
          if ((x - cx) * (x - cx) + (y - cy) * (y - cy) > r * r || depth[i] < z) continue;
          depth[i] = z;
          for (int c = 0; c < 3; ++c)
            display.pixels[3 * i + c] = grey + 0.05f * float(random.next());
        }
    }
    return make_image_view(display, depth, DisplayEncoding::srgb(), 8);
  }();
  return view;
}

// Spatial importance (normalise, blur, ΔD) plus the darken composition.
double kernel_sigma_px(double kernel_percent) {
  ImageWidth width;
  width.kernel_percent = kernel_percent;
  return width.sigma_px_for(kWidth, kHeight);
}

void BM_DepthUsm(benchmark::State& state) {
  const nlohmann::json options = {{"operator", "darken"},
                                  {"kernel_percent", double(state.range(0))}};
  for (auto _ : state) {
    Composed out = prepare_method("depth-usm", test_view(), options)->compose(1.0);
    benchmark::DoNotOptimize(out.display.pixels.data());
  }
  state.counters["sigma_px"] = kernel_sigma_px(double(state.range(0)));
}
BENCHMARK(BM_DepthUsm)->Arg(1)->Arg(5)->Unit(benchmark::kMillisecond)->UseRealTime();

// One further λ of a prepared view: the darken composition alone.
void BM_DepthUsmCompose(benchmark::State& state) {
  auto prepared =
      prepare_method("depth-usm", test_view(), {{"operator", "darken"}, {"kernel_percent", 5}});
  for (auto _ : state) {
    Composed out = prepared->compose(1.0);
    benchmark::DoNotOptimize(out.display.pixels.data());
  }
}
BENCHMARK(BM_DepthUsmCompose)->Unit(benchmark::kMillisecond)->UseRealTime();

// The spatial importance function alone (normalise D, blur, ΔD = G*D − D).
void BM_SpatialImportance(benchmark::State& state) {
  const View& view = *test_view();
  const double sigma = kernel_sigma_px(double(state.range(0)));
  for (auto _ : state) {
    SpatialImportance si = spatial_importance(view, DepthMapping{}, sigma);
    benchmark::DoNotOptimize(si.importance.pixels.data());
  }
}
BENCHMARK(BM_SpatialImportance)->Arg(1)->Arg(5)->Unit(benchmark::kMillisecond)->UseRealTime();

// The outline sampling of a rendered view (4×4 primary rays over every pixel at a depth edge,
// enhance/depth_coverage.h) against the per-pixel rule on the same pixels and depth: the clutter
// scene at 1920×1080, K = 5 %. Arg 0: the rendered view; 1: its image and depth as an image view.
void BM_SpatialImportanceOutlines(benchmark::State& state) {
  static const std::shared_ptr<const View> rendered = [] {
    auto scene = std::make_shared<Scene>(
        load_scene(std::string(COUNTERSHADE_SOURCE_DIR) + "/experiments/scenes/clutter.json"));
    scene->camera.width = kWidth;
    scene->camera.height = kHeight;
    scene->settings.spp = 1;
    return render_view(scene);
  }();
  static const std::shared_ptr<const View> image =
      make_image_view(rendered->display, rendered->depth, rendered->encoding, 8);
  const View& view = state.range(0) == 0 ? *rendered : *image;
  for (auto _ : state) {
    SpatialImportance si = spatial_importance(view, {}, kernel_sigma_px(5));
    benchmark::DoNotOptimize(si.darker.pixels.data());
  }
}
BENCHMARK(BM_SpatialImportanceOutlines)
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The recursive Gaussian alone on a 1920×1080 float plane (σ in px).
void BM_GaussianBlur(benchmark::State& state) {
  const View& view = *test_view();
  std::vector<float> out(view.depth.size());
  for (auto _ : state) {
    gaussian_blur(view.depth.data(), out.data(), kWidth, kHeight, double(state.range(0)));
    benchmark::DoNotOptimize(out.data());
  }
}
BENCHMARK(BM_GaussianBlur)->Arg(6)->Arg(28)->Unit(benchmark::kMillisecond)->UseRealTime();

// K = 5% against K = 1%, timed alternately in one run.
void BM_DepthUsmKernelRatio(benchmark::State& state) {
  const nlohmann::json small = {{"kernel_percent", 1.0}}, large = {{"kernel_percent", 5.0}};
  std::vector<double> t1, t5;
  for (auto _ : state) {
    for (auto [options, times] : {std::pair{&small, &t1}, std::pair{&large, &t5}}) {
      const auto start = std::chrono::steady_clock::now();
      Composed out = prepare_method("depth-usm", test_view(), *options)->compose(1.0);
      benchmark::DoNotOptimize(out.display.pixels.data());
      lap(start, *times);
    }
  }
  state.counters["median_K1_ms"] = 1e3 * median(t1);
  state.counters["median_K5_ms"] = 1e3 * median(t5);
  state.counters["K5/K1"] = median(t5) / median(t1);
}
BENCHMARK(BM_DepthUsmKernelRatio)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(15);

// 2D unsharp masking end to end at σ = 1% of the diagonal, from the display image: its CIELAB
// conversion, the blur of L*, and one composition; the counters give each step's median.
void BM_Usm2dEndToEnd(benchmark::State& state) {
  const View& view = *test_view();
  std::vector<double> convert, prepare, compose;
  for (auto _ : state) {
    auto t = std::chrono::steady_clock::now();
    // Included: a view's CIELAB and L* plane, which the method reads, are part of its cost.
    PixelVector lightness;
    LabPixels lab = display_to_lab(view.display, view.encoding, view.bits, &lightness);
    benchmark::DoNotOptimize(lab.data());
    t = lap(t, convert);
    auto prepared = prepare_method("usm2d", test_view(), {{"sigma_percent", 1.0}});
    t = lap(t, prepare);
    Composed out = prepared->compose(1.0);
    benchmark::DoNotOptimize(out.display.pixels.data());
    lap(t, compose);
  }
  state.counters["convert_ms"] = 1e3 * median(convert);
  state.counters["prepare_ms"] = 1e3 * median(prepare);
  state.counters["compose_ms"] = 1e3 * median(compose);
}
BENCHMARK(BM_Usm2dEndToEnd)->Unit(benchmark::kMillisecond)->UseRealTime();

// The once-per-σ preparation of 2D unsharp masking alone (L*, its blur and the detail).
void BM_Usm2dPrepare(benchmark::State& state) {
  for (auto _ : state) {
    auto prepared = prepare_method("usm2d", test_view(), {{"sigma_percent", 1.0}});
    benchmark::DoNotOptimize(prepared.get());
  }
}
BENCHMARK(BM_Usm2dPrepare)->Unit(benchmark::kMillisecond)->UseRealTime();

// The CIELAB conversion of a display image alone (with its L* plane, as views make it).
void BM_DisplayToLab(benchmark::State& state) {
  const View& view = *test_view();
  for (auto _ : state) {
    PixelVector lightness;  // as views make it
    LabPixels lab = display_to_lab(view.display, view.encoding, view.bits, &lightness);
    benchmark::DoNotOptimize(lab.data());
  }
}
BENCHMARK(BM_DisplayToLab)->Unit(benchmark::kMillisecond)->UseRealTime();

// OpenImageIO's Gaussian `width` is its kernel's support; find the width whose kernel has the σ
// we want, by measuring the kernel OpenImageIO builds.
float oiio_width_for_sigma(double sigma) {
  auto kernel_sigma = [](float width) {
    OIIO::ImageBuf k = OIIO::ImageBufAlgo::make_kernel("gaussian", width, 1.0f);
    const OIIO::ImageSpec& s = k.spec();
    double sum = 0, var = 0, centre = (s.width - 1) / 2.0 + s.x;
    for (int x = s.x; x < s.x + s.width; ++x) {
      float v;
      k.getpixel(x, s.y, &v, 1);
      sum += v;
      var += v * (x - centre) * (x - centre);
    }
    return std::sqrt(var / sum);
  };
  float lo = 1.0f, hi = float(20 * sigma);
  for (int i = 0; i < 40; ++i) {
    float mid = 0.5f * (lo + hi);
    (kernel_sigma(mid) < sigma ? lo : hi) = mid;
  }
  return 0.5f * (lo + hi);
}

// 2D unsharp masking at σ = 1% of the diagonal: countershade (lightness, from the display image:
// CIELAB conversion, blur, composition) against OpenImageIO's unsharp_mask (RGB) in the same run.
void BM_Usm2dVersusOiio(benchmark::State& state) {
  const View& view = *test_view();
  ImageWidth one_percent;
  one_percent.sigma_percent = 1.0;
  const double sigma = one_percent.sigma_px_for(kWidth, kHeight);
  const float width = oiio_width_for_sigma(sigma);
  OIIO::ImageBuf src(OIIO::ImageSpec(kWidth, kHeight, 3, OIIO::TypeDesc::FLOAT),
                     (void*)view.display.pixels.data());
  OIIO::ImageBuf dst;
  std::vector<double> ours, theirs;
  for (auto _ : state) {
    auto t = std::chrono::steady_clock::now();
    // Included: a view's CIELAB and L* plane, which the method reads, are part of its cost.
    PixelVector lightness;
    LabPixels lab = display_to_lab(view.display, view.encoding, view.bits, &lightness);
    benchmark::DoNotOptimize(lab.data());
    Composed out = prepare_method("usm2d", test_view(), {{"sigma_percent", 1.0}})->compose(1.0);
    benchmark::DoNotOptimize(out.display.pixels.data());
    t = lap(t, ours);
    OIIO::ImageBufAlgo::unsharp_mask(dst, src, "gaussian", width, 1.0f, 0.0f);
    lap(t, theirs);
  }
  state.counters["sigma_px"] = sigma;
  state.counters["oiio_width"] = width;
  state.counters["countershade_ms"] = 1e3 * median(ours);
  state.counters["oiio_ms"] = 1e3 * median(theirs);
  state.counters["oiio/countershade"] = median(theirs) / median(ours);
}
// OpenImageIO convolves with the full 2D kernel here (about a minute per run), so one iteration.
BENCHMARK(BM_Usm2dVersusOiio)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace
}  // namespace countershade
