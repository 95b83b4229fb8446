#include "enhance/lightness.h"

#include <algorithm>
#include <atomic>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/parallel.h"

namespace countershade {

Lab display_pixel_to_lab(const float* rgb, const DisplayEncoding& encoding) {
  return linear_rgb_to_lab({encoding.decode(rgb[0]), encoding.decode(rgb[1]), encoding.decode(rgb[2])});
}

std::vector<Lab> display_to_lab(const Image& display, const DisplayEncoding& encoding) {
  std::vector<Lab> lab(size_t(display.width) * display.height);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, lab.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) lab[i] = display_pixel_to_lab(&display.pixels[3 * i], encoding);
  });
  return lab;
}

Composed compose_lightness(const View& view, const LightnessChange& change, double lambda, int threads) {
  Composed out;
  out.display = view.display;
  std::atomic<size_t> clipped{0};
  const std::vector<Lab>& lab = view.lab;
  const DisplayEncoding& encoding = view.encoding;
  parallel_ranges(
      lab.size(), threads,
      [&](size_t begin, size_t end) {
        size_t local = 0;
        for (size_t i = begin; i != end; ++i) {
          const double delta = change.delta(i, lambda);
          if (delta == 0.0) continue;
          double target = lab[i].L + delta;
          bool clip = target < 0.0 || target > 100.0;
          glm::dvec3 rgb = lab_to_linear_rgb(with_lightness(lab[i], target));
          for (int c = 0; c < 3; ++c) {
            clip |= rgb[c] < -1e-9 || rgb[c] > 1.0 + 1e-9;
            out.display.pixels[3 * i + c] = float(encoding.encode(std::clamp(rgb[c], 0.0, 1.0)));
          }
          local += clip;
        }
        clipped += local;
      },
      2048);
  out.clipped_pixels = clipped;
  return out;
}

}  // namespace countershade
