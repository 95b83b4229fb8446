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

// Filters columns [x0, x1) of a row-major image along y. All columns of a row are independent, so
// the inner loops run over x without branches and vectorise; rows outside the image are the edge
// rows (clamp-to-edge) with the recursion at its steady state there.
// Compiled twice: for AVX2/FMA machines and for the x86-64 baseline, chosen at load time.
__attribute__((target_clones("arch=x86-64-v3", "default")))
void deriche_columns(const float* in, float* out, int width, int height, int x0, int x1, const Deriche& f,
                     std::vector<double>& scratch) {
  const size_t w = size_t(x1 - x0);
  // Causal outputs for rows -4..height-1 (4 leading rows of steady state).
  scratch.resize((size_t(height) + 4) * w);
  double* causal = scratch.data() + 4 * w;
  const float* first = in + x0;
  const float* last = in + size_t(height - 1) * width + x0;
  for (int k = 1; k <= 4; ++k)
    for (size_t i = 0; i < w; ++i) causal[-long(k) * long(w) + long(i)] = f.causal_gain * first[i];
  auto row = [&](int y) { return in + size_t(std::clamp(y, 0, height - 1)) * width + x0; };
  const double n0 = f.n[0], n1 = f.n[1], n2 = f.n[2], n3 = f.n[3];
  const double m0 = f.m[0], m1 = f.m[1], m2 = f.m[2], m3 = f.m[3];
  const double d0 = f.d[0], d1 = f.d[1], d2 = f.d[2], d3 = f.d[3];
  for (int y = 0; y < height; ++y) {
    const float *x_0 = row(y), *x_1 = row(y - 1), *x_2 = row(y - 2), *x_3 = row(y - 3);
    double* c = causal + size_t(y) * w;
    const double *c1 = c - w, *c2 = c - 2 * w, *c3 = c - 3 * w, *c4 = c - 4 * w;
    for (size_t i = 0; i < w; ++i)
      c[i] = n0 * x_0[i] + n1 * x_1[i] + n2 * x_2[i] + n3 * x_3[i] - (d0 * c1[i] + d1 * c2[i] + d2 * c3[i] + d3 * c4[i]);
  }
  // Anticausal pass from the last row; the last 4 outputs live in a ring, seeded at steady state.
  std::vector<double> ring(4 * w);
  for (int k = 0; k < 4; ++k)
    for (size_t i = 0; i < w; ++i) ring[size_t(k) * w + i] = f.anticausal_gain * last[i];
  for (int y = height - 1; y >= 0; --y) {
    const float *x_1 = row(y + 1), *x_2 = row(y + 2), *x_3 = row(y + 3), *x_4 = row(y + 4);
    // Ring slot of row r is r mod 4 (rows past the end hold the steady state already).
    double* a0 = &ring[size_t(y & 3) * w];  // becomes row y; holds row y+4 until written
    const double *a1 = &ring[size_t((y + 1) & 3) * w], *a2 = &ring[size_t((y + 2) & 3) * w],
                 *a3 = &ring[size_t((y + 3) & 3) * w];
    const double* c = causal + size_t(y) * w;
    float* o = out + size_t(y) * width + x0;
    for (size_t i = 0; i < w; ++i) {
      double a = m0 * x_1[i] + m1 * x_2[i] + m2 * x_3[i] + m3 * x_4[i] - (d0 * a1[i] + d1 * a2[i] + d2 * a3[i] + d3 * a0[i]);
      a0[i] = a;
      o[i] = float(c[i] + a);
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

// Filters every row along x, in place: blocks of 16 rows are transposed into a small buffer that
// stays in cache, filtered as columns, and transposed back.
void recursive_horizontal(float* image, int width, int height, const Deriche& f, tbb::task_arena& arena) {
  constexpr int kRows = 32;
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, (height + kRows - 1) / kRows), [&](const tbb::blocked_range<int>& r) {
      std::vector<float> block(size_t(width) * kRows), filtered(block.size());
      std::vector<double> scratch;
      for (int b = r.begin(); b != r.end(); ++b) {
        int y0 = b * kRows, rows = std::min(kRows, height - y0);
        for (int k = 0; k < rows; ++k)
          for (int x = 0; x < width; ++x) block[size_t(x) * rows + k] = image[size_t(y0 + k) * width + x];
        deriche_columns(block.data(), filtered.data(), rows, width, 0, rows, f, scratch);
        for (int k = 0; k < rows; ++k)
          for (int x = 0; x < width; ++x) image[size_t(y0 + k) * width + x] = filtered[size_t(x) * rows + k];
      }
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
  if (in == out) {  // the vertical pass reads rows it has already written otherwise
    std::vector<float> copy(in, in + size_t(width) * height);
    recursive_vertical(copy.data(), out, width, height, filter, arena);
  } else {
    recursive_vertical(in, out, width, height, filter, arena);
  }
  recursive_horizontal(out, width, height, filter, arena);
}

}  // namespace countershade
