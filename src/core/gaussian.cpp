#include "core/gaussian.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace countershade {
namespace {

// Deriche's 4th-order approximation with Farnebäck and Westin's (2006) constants: a causal and
// an anticausal recursion whose sum approximates convolution with a unit-area Gaussian.
// The recursion runs in double: for large σ its poles approach 1 and float loses accuracy.
struct Deriche {
  double n[4], m[4], d[4];
  double causal_gain, anticausal_gain;  // steady-state response to a constant input, for the borders

  explicit Deriche(double sigma) {
    const double a1 = 1.3530, b1 = 1.8151, w1 = 0.6681, l1 = -1.3932;
    const double a2 = -0.3531, b2 = 0.0902, w2 = 2.0787, l2 = -1.3732;
    double s1 = std::sin(w1 / sigma), s2 = std::sin(w2 / sigma);
    double c1 = std::cos(w1 / sigma), c2 = std::cos(w2 / sigma);
    double e1 = std::exp(l1 / sigma), e2 = std::exp(l2 / sigma);
    double N[4], D[4], M[4];
    N[0] = a1 + a2;
    N[1] = e2 * (b2 * s2 - (a2 + 2 * a1) * c2) + e1 * (b1 * s1 - (a1 + 2 * a2) * c1);
    N[2] = 2 * e1 * e2 * ((a1 + a2) * c2 * c1 - b1 * c2 * s1 - b2 * c1 * s2) + a2 * e1 * e1 + a1 * e2 * e2;
    N[3] = e2 * e1 * e1 * (b2 * s2 - a2 * c2) + e1 * e2 * e2 * (b1 * s1 - a1 * c1);
    D[0] = -2 * (e2 * c2 + e1 * c1);
    D[1] = 4 * c2 * c1 * e1 * e2 + e1 * e1 + e2 * e2;
    D[2] = -2 * c1 * e1 * e2 * e2 - 2 * c2 * e2 * e1 * e1;
    D[3] = e1 * e1 * e2 * e2;
    double sum_d = 1 + D[0] + D[1] + D[2] + D[3];
    double sum_n = N[0] + N[1] + N[2] + N[3];
    double scale = 2 * sum_n / sum_d - N[0];  // unit area of causal + anticausal response
    for (double& v : N) v /= scale;
    M[0] = N[1] - D[0] * N[0];
    M[1] = N[2] - D[1] * N[0];
    M[2] = N[3] - D[2] * N[0];
    M[3] = -D[3] * N[0];
    double sum_m = M[0] + M[1] + M[2] + M[3];
    sum_n = N[0] + N[1] + N[2] + N[3];
    for (int k = 0; k < 4; ++k) {
      n[k] = N[k];
      m[k] = M[k];
      d[k] = D[k];
    }
    causal_gain = sum_n / sum_d;
    anticausal_gain = sum_m / sum_d;
  }
};

// Filters columns [x0, x1) of a row-major image along y (all columns of a row are independent,
// so the inner loops over x vectorise). `causal` is scratch of height×(x1-x0).
void deriche_columns(const float* in, float* out, int width, int height, int x0, int x1, const Deriche& f,
                     std::vector<double>& causal) {
  const int w = x1 - x0;
  causal.resize(size_t(height) * w);
  auto at = [&](const float* img, int y, int x) { return img[size_t(y) * width + x]; };
  // Causal pass; rows before the first are the first row (clamp-to-edge) at steady state.
  for (int y = 0; y < height; ++y) {
    double* yc = &causal[size_t(y) * w];
    for (int i = 0; i < w; ++i) {
      int x = x0 + i;
      double x_first = at(in, 0, x);
      double xin[4], yprev[4];
      for (int k = 0; k < 4; ++k) {
        int yy = y - k;
        xin[k] = yy >= 0 ? at(in, yy, x) : x_first;
        int py = y - 1 - k;
        yprev[k] = py >= 0 ? causal[size_t(py) * w + i] : f.causal_gain * x_first;
      }
      yc[i] = f.n[0] * xin[0] + f.n[1] * xin[1] + f.n[2] * xin[2] + f.n[3] * xin[3] -
              (f.d[0] * yprev[0] + f.d[1] * yprev[1] + f.d[2] * yprev[2] + f.d[3] * yprev[3]);
    }
  }
  // Anticausal pass from the last row, added to the causal result. Keeps the last 4 outputs.
  std::vector<double> ring(size_t(4) * w);
  for (int y = height - 1; y >= 0; --y) {
    for (int i = 0; i < w; ++i) {
      int x = x0 + i;
      double x_last = at(in, height - 1, x);
      double xin[4], ynext[4];
      for (int k = 0; k < 4; ++k) {
        int yy = y + 1 + k;
        xin[k] = yy < height ? at(in, yy, x) : x_last;
        ynext[k] = yy < height ? ring[size_t(yy % 4) * w + i] : f.anticausal_gain * x_last;
      }
      double ya = f.m[0] * xin[0] + f.m[1] * xin[1] + f.m[2] * xin[2] + f.m[3] * xin[3] -
                 (f.d[0] * ynext[0] + f.d[1] * ynext[1] + f.d[2] * ynext[2] + f.d[3] * ynext[3]);
      ring[size_t(y % 4) * w + i] = ya;
      out[size_t(y) * width + x] = float(causal[size_t(y) * w + i] + ya);
    }
  }
}

void transpose(const float* in, float* out, int width, int height, tbb::task_arena& arena) {
  constexpr int kBlock = 32;
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, (height + kBlock - 1) / kBlock), [&](const tbb::blocked_range<int>& r) {
      for (int by = r.begin(); by != r.end(); ++by)
        for (int bx = 0; bx < width; bx += kBlock)
          for (int y = by * kBlock; y < std::min(height, (by + 1) * kBlock); ++y)
            for (int x = bx; x < std::min(width, bx + kBlock); ++x)
              out[size_t(x) * height + y] = in[size_t(y) * width + x];
    });
  });
}

void recursive_vertical(const float* in, float* out, int width, int height, const Deriche& f, tbb::task_arena& arena) {
  constexpr int kColumns = 256;
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, (width + kColumns - 1) / kColumns),
                      [&](const tbb::blocked_range<int>& r) {
                        std::vector<double> scratch;
                        for (int b = r.begin(); b != r.end(); ++b)
                          deriche_columns(in, out, width, height, b * kColumns,
                                          std::min(width, (b + 1) * kColumns), f, scratch);
                      });
  });
}

// Exact FIR along x for every row (in double), clamp-to-edge.
void fir_rows(const float* in, float* out, int width, int height, const std::vector<double>& kernel,
              tbb::task_arena& arena) {
  const int radius = int(kernel.size() / 2);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& r) {
      std::vector<double> row(static_cast<size_t>(width));
      for (int y = r.begin(); y != r.end(); ++y) {
        const float* src = in + size_t(y) * width;
        for (int x = 0; x < width; ++x) {
          double sum = 0;
          for (int k = -radius; k <= radius; ++k) sum += kernel[size_t(k + radius)] * src[std::clamp(x + k, 0, width - 1)];
          row[size_t(x)] = sum;
        }
        for (int x = 0; x < width; ++x) out[size_t(y) * width + x] = float(row[size_t(x)]);
      }
    });
  });
}

std::vector<double> gaussian_kernel(double sigma) {
  int radius = std::max(1, int(std::ceil(4.0 * sigma)));
  std::vector<double> k(size_t(2 * radius + 1));
  double sum = 0;
  for (int i = -radius; i <= radius; ++i) sum += k[size_t(i + radius)] = std::exp(-0.5 * i * i / (sigma * sigma));
  for (double& v : k) v /= sum;
  return k;
}

void check(int width, int height, double sigma) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("gaussian_blur: empty image");
  if (!(sigma > 0) || !std::isfinite(sigma)) throw std::invalid_argument("gaussian_blur: sigma must be positive");
}

}  // namespace

void gaussian_blur_exact(const float* in, float* out, int width, int height, double sigma, int threads) {
  check(width, height, sigma);
  tbb::task_arena arena(threads > 0 ? threads : tbb::this_task_arena::max_concurrency());
  std::vector<double> kernel = gaussian_kernel(sigma);
  std::vector<float> a(size_t(width) * height), b(a.size());
  fir_rows(in, a.data(), width, height, kernel, arena);
  transpose(a.data(), b.data(), width, height, arena);
  fir_rows(b.data(), a.data(), height, width, kernel, arena);
  transpose(a.data(), out, height, width, arena);
}

void gaussian_blur(const float* in, float* out, int width, int height, double sigma, int threads) {
  check(width, height, sigma);
  if (sigma < kRecursiveMinSigma) return gaussian_blur_exact(in, out, width, height, sigma, threads);
  tbb::task_arena arena(threads > 0 ? threads : tbb::this_task_arena::max_concurrency());
  Deriche filter(sigma);
  std::vector<float> a(size_t(width) * height), b(a.size());
  recursive_vertical(in, a.data(), width, height, filter, arena);      // along y
  transpose(a.data(), b.data(), width, height, arena);
  recursive_vertical(b.data(), a.data(), height, width, filter, arena);  // along x (transposed)
  transpose(a.data(), out, height, width, arena);
}

}  // namespace countershade
