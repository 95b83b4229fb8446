#include "enhance/lightness_filters.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace countershade {
namespace {

int border_index(int i, int n, Borders borders) {
  if (borders == Borders::clamp) return std::clamp(i, 0, n - 1);
  return ((i % n) + n) % n;
}

std::vector<double> gaussian_weights(double sigma, int radius) {
  std::vector<double> w(size_t(2 * radius + 1));
  double sum = 0;
  for (int k = -radius; k <= radius; ++k)
    sum += w[size_t(k + radius)] = std::exp(-0.5 * k * k / (sigma * sigma));
  for (double& v : w) v /= sum;
  return w;
}

// One pass along x (stride 1, `count` = width, `lines` = height) or y (stride width).
void gaussian_pass(const std::vector<double>& in, std::vector<double>& out, int count, int lines,
                   size_t stride, size_t line_stride, double sigma, Borders borders, int threads) {
  const int radius = int(std::ceil(4 * sigma));
  const std::vector<double> w = gaussian_weights(sigma, radius);
  parallel_ranges(size_t(lines), threads, [&](size_t begin, size_t end) {
    for (size_t line = begin; line < end; ++line)
      for (int i = 0; i < count; ++i) {
        double sum = 0;
        for (int k = -radius; k <= radius; ++k)
          sum += w[size_t(k + radius)] *
                 in[line * line_stride + size_t(border_index(i + k, count, borders)) * stride];
        out[line * line_stride + size_t(i) * stride] = sum;
      }
  });
}

double bilateral_at(std::span<const float> L, int width, int height, int x, int y,
                    const LightnessFilter& f, const std::vector<double>& spatial, int radius,
                    Borders borders) {
  const double centre = L[size_t(y) * size_t(width) + size_t(x)],
               range = -0.5 / (f.sigma_r * f.sigma_r);
  double sum = 0, weight = 0;
  for (int j = -radius; j <= radius; ++j) {
    const size_t row = size_t(border_index(y + j, height, borders)) * size_t(width);
    for (int i = -radius; i <= radius; ++i) {
      const double v = L[row + size_t(border_index(x + i, width, borders))], d = v - centre;
      const double w =
          spatial[size_t(j + radius)] * spatial[size_t(i + radius)] * std::exp(range * d * d);
      sum += w * v;
      weight += w;
    }
  }
  return sum / weight;
}

std::vector<float> bilateral_detail(std::span<const float> L, int width, int height,
                                    const LightnessFilter& f, Borders borders, int threads) {
  const int radius = int(std::ceil(3 * f.sigma));
  std::vector<double> spatial(size_t(2 * radius + 1));
  for (int k = -radius; k <= radius; ++k)
    spatial[size_t(k + radius)] = std::exp(-0.5 * k * k / (f.sigma * f.sigma));
  std::vector<float> d(L.size());
  parallel_ranges(size_t(height), threads, [&](size_t begin, size_t end) {
    for (size_t y = begin; y < end; ++y)
      for (int x = 0; x < width; ++x) {
        const size_t i = y * size_t(width) + size_t(x);
        d[i] = float(bilateral_at(L, width, height, x, int(y), f, spatial, radius, borders) - L[i]);
      }
  });
  return d;
}

}  // namespace

std::string filter_name(FilterKind kind) {
  switch (kind) {
    case FilterKind::unsharp:
      return "unsharp";
    case FilterKind::bilateral:
      return "bilateral";
    case FilterKind::dog:
      return "dog";
  }
  return "";
}

LightnessFilter read_lightness_filter(const ParameterBag& bag) {
  LightnessFilter f;
  const std::string filter = bag.choice("filter", "unsharp", {"unsharp", "bilateral", "dog"});
  f.kind = filter == "unsharp" ? FilterKind::unsharp
                               : (filter == "bilateral" ? FilterKind::bilateral : FilterKind::dog);
  if (bag.has("sigma_r") && f.kind != FilterKind::bilateral)
    bag.fail("sigma_r", "applies to filter bilateral only");
  for (const char* key : {"tau", "phi"})
    if (bag.has(key) && f.kind != FilterKind::dog) bag.fail(key, "applies to filter dog only");
  f.sigma = bag.number_in("sigma", 2.0, 0.1, 256.0);
  // The bilateral window is (2⌈3σ⌉ + 1)² samples per sample: σ = 8 already costs 2401.
  if (f.kind == FilterKind::bilateral && f.sigma > kMaxBilateralSigma)
    bag.fail("sigma", "must be at most " + std::to_string(int(kMaxBilateralSigma)) +
                          " for filter bilateral (its cost grows with σ²)");
  f.sigma_r = bag.number_in("sigma_r", 10.0, 0.01, 1000.0);
  f.tau = bag.number_in("tau", 1.0, 0.0, 100.0);
  f.phi = bag.number_in("phi", 0.5, 1e-3, 100.0);
  return f;
}

std::vector<double> gaussian_filter(std::span<const float> plane, int width, int height,
                                    double sigma, Borders borders, int threads) {
  std::vector<double> a(plane.begin(), plane.end()), b(a.size());
  gaussian_pass(a, b, width, height, 1, size_t(width), sigma, borders, threads);
  gaussian_pass(b, a, height, width, size_t(width), 1, sigma, borders, threads);
  return a;
}

std::vector<float> lightness_detail(std::span<const float> L, int width, int height,
                                    const LightnessFilter& f, Borders borders, int threads) {
  if (f.kind == FilterKind::bilateral)
    return bilateral_detail(L, width, height, f, borders, threads);
  const std::vector<double> fine = gaussian_filter(L, width, height, f.sigma, borders, threads);
  std::vector<float> d(L.size());
  if (f.kind == FilterKind::unsharp) {
    for (size_t i = 0; i < d.size(); ++i) d[i] = float(double(L[i]) - fine[i]);
    return d;
  }
  const std::vector<double> coarse =
      gaussian_filter(L, width, height, 1.6 * f.sigma, borders, threads);
  for (size_t i = 0; i < d.size(); ++i) {
    const double D = fine[i] - coarse[i];
    const double edge = D >= -f.tau ? 1.0 : 1.0 + std::tanh(f.phi * (D + f.tau));
    d[i] = float(-(1.0 - edge) * double(L[i]));
  }
  return d;
}

}  // namespace countershade
