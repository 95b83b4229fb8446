// Fits the constants of the 4th-order recursive Gaussian in src/core/gaussian.cpp: a Nelder–Mead
// search, with restarts, for the (a, b, w, l) that minimise the worst step-response error against
// the sampled, normalised Gaussian (the exact FIR) over several σ. Run:
// build/bin/fit_recursive_gaussian (about a minute); it prints the constants and the error at each
// σ.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <vector>

namespace {

using Constants = std::array<double, 8>;  // a0 a1 b0 b1 w0 w1 l0 l1

// The recursion's impulse response: h(|n|), normalised to unit area, as gaussian.cpp builds it.
std::vector<double> recursive_kernel(const Constants& c, double sigma, int radius) {
  std::vector<double> h(size_t(radius) + 1);
  for (int n = 0; n <= radius; ++n)
    for (int k = 0; k < 2; ++k) {
      const double e = std::exp(c[6 + k] / sigma), theta = c[4 + k] / sigma;
      h[size_t(n)] +=
          std::pow(e, n) * (c[k] * std::cos(n * theta) + c[2 + k] * std::sin(n * theta));
    }
  return h;
}

// The exact FIR's kernel: exp(−n²/2σ²) for |n| ≤ ⌈4σ⌉.
std::vector<double> sampled_gaussian(double sigma, int radius) {
  std::vector<double> g(size_t(radius) + 1);
  const int support = std::max(1, int(std::ceil(4 * sigma)));
  for (int n = 0; n <= std::min(radius, support); ++n)
    g[size_t(n)] = std::exp(-0.5 * n * n / (sigma * sigma));
  return g;
}

double symmetric_area(const std::vector<double>& half) {
  return 2 * std::accumulate(half.begin(), half.end(), 0.0) - half[0];
}

double step_error(const Constants& c, double sigma) {
  const int radius = int(12 * sigma) + 10;
  const auto h = recursive_kernel(c, sigma, radius), g = sampled_gaussian(sigma, radius);
  const double h_area = symmetric_area(h), g_area = symmetric_area(g);
  double step = 0, worst = 0;
  for (int n = -radius; n <= radius; ++n) {
    step += h[size_t(std::abs(n))] / h_area - g[size_t(std::abs(n))] / g_area;
    worst = std::max(worst, std::abs(step));
  }
  return worst;
}

double worst_step_error(const Constants& c) {
  double worst = 0;
  for (double sigma : {3.0, 4.0, 6.0, 10.0, 25.0, 60.0})
    worst = std::max(worst, step_error(c, sigma));
  return worst;
}

// One Nelder–Mead run from `start`, with an initial simplex of relative size `scale`.
Constants nelder_mead(const Constants& start, double scale, int iterations) {
  constexpr int N = 8;
  std::array<Constants, N + 1> x;
  std::array<double, N + 1> f;
  for (int i = 0; i <= N; ++i) {
    x[size_t(i)] = start;
    if (i > 0) x[size_t(i)][size_t(i - 1)] *= 1 + scale;
    f[size_t(i)] = worst_step_error(x[size_t(i)]);
  }
  for (int it = 0; it < iterations; ++it) {
    std::array<int, N + 1> order;
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return f[size_t(a)] < f[size_t(b)]; });
    auto xs = x;
    auto fs = f;
    for (int i = 0; i <= N; ++i)
      x[size_t(i)] = xs[size_t(order[size_t(i)])], f[size_t(i)] = fs[size_t(order[size_t(i)])];
    Constants centre{};
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < N; ++j) centre[size_t(j)] += x[size_t(i)][size_t(j)] / N;
    auto along = [&](double t) {
      Constants r;
      for (int j = 0; j < N; ++j)
        r[size_t(j)] = centre[size_t(j)] + t * (x[N][size_t(j)] - centre[size_t(j)]);
      return r;
    };
    const Constants reflected = along(-1);
    const double fr = worst_step_error(reflected);
    if (fr < f[0]) {
      const Constants expanded = along(-2);
      const double fe = worst_step_error(expanded);
      x[N] = fe < fr ? expanded : reflected, f[N] = std::min(fe, fr);
    } else if (fr < f[N - 1]) {
      x[N] = reflected, f[N] = fr;
    } else if (const Constants contracted = along(0.5); worst_step_error(contracted) < f[N]) {
      x[N] = contracted, f[N] = worst_step_error(contracted);
    } else {
      for (int i = 1; i <= N; ++i) {
        for (int j = 0; j < N; ++j)
          x[size_t(i)][size_t(j)] =
              x[0][size_t(j)] + 0.5 * (x[size_t(i)][size_t(j)] - x[0][size_t(j)]);
        f[size_t(i)] = worst_step_error(x[size_t(i)]);
      }
    }
  }
  return x[size_t(std::min_element(f.begin(), f.end()) - f.begin())];
}

}  // namespace

int main() {
  Constants c = {1.3530, -0.3531, 1.8151,  0.0902,
                 0.6681, 2.0787,  -1.3932, -1.3732};  // the 4-digit constants
  std::printf("start: worst step error %.3e\n", worst_step_error(c));
  for (int restart = 0; restart < 30; ++restart) c = nelder_mead(c, 0.02 / (1 + restart), 4000);
  std::printf("fitted: worst step error %.3e\nconstants:", worst_step_error(c));
  for (double v : c) std::printf(" %.10f", v);
  std::printf("\n");
  for (double sigma : {3.0, 5.0, 10.0, 40.0, 100.0, 300.0})
    std::printf("sigma %5g: %.3e\n", sigma, step_error(c, sigma));
}
