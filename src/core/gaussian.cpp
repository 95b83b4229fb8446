#include "core/gaussian.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "core/image.h"
#include "core/parallel.h"

namespace countershade {
namespace {

// Deriche's 4th-order approximation: a causal and an anticausal recursion whose sum approximates
// convolution with a unit-area Gaussian. The causal impulse response is a sum of two damped
// oscillations, h(n) = Σ_k e_k^n (a_k cos nθ_k + b_k sin nθ_k), with e_k = exp(l_k/σ) and
// θ_k = w_k/σ, so the filter runs as two second-order sections in parallel. Unlike the direct
// 4th-order form, these stay accurate in float even for large σ (poles near 1), which doubles the
// vector width of the recursion. Coefficients are computed in double.
//
// The constants (a, b, w, l) are a minimax fit of the step response to the sampled Gaussian over
// σ = 3…60 (bench/fit_recursive_gaussian.cpp): the step response is then within 8.2e-5 of the
// exact FIR for every σ from 3 to 300 px. The commonly quoted 4-digit constants
// (a = 1.3530, −0.3531; b = 1.8151, 0.0902; w = 0.6681, 2.0787; l = −1.3932, −1.3732) miss by
// 1.35e-3 of a step.
struct Deriche {
  struct Section {
    double n0, n1;  // causal numerator: y(n) = n0 x(n) + n1 x(n−1) − d1 y(n−1) − d2 y(n−2)
    double m1, m2;  // anticausal numerator: y(n) = m1 x(n+1) + m2 x(n+2) − d1 y(n+1) − d2 y(n+2)
    double d1, d2;
    double causal_gain,
        anticausal_gain;  // steady-state response to a constant input, for the borders
  } section[2];
  // Above this σ the poles are so close to 1 that float coefficients and sums lose the accuracy
  // (3.3e-4 of a step at σ = 100, 2.6e-3 at σ = 500); the recursion then runs in double.
  static constexpr double kDoubleAboveSigma = 48;
  bool in_double;

  explicit Deriche(double sigma) : in_double(sigma > kDoubleAboveSigma) {
    const double a[2] = {1.0280210277, -0.4095251455}, b[2] = {1.7398432004, 0.0344188866};
    const double w[2] = {0.5904286671, 1.8836736010}, l[2] = {-1.6743034363, -1.5538501598};
    double h[2][3], d1[2], d2[2];
    for (int k = 0; k < 2; ++k) {
      const double e = std::exp(l[k] / sigma), theta = w[k] / sigma;
      for (int n = 0; n < 3; ++n)
        h[k][n] = std::pow(e, n) * (a[k] * std::cos(n * theta) + b[k] * std::sin(n * theta));
      d1[k] = -2 * e * std::cos(theta);
      d2[k] = e * e;
    }
    // Unit area of the whole (causal + anticausal) response, from the sections' transfer functions
    // at z = 1.
    double area = 0;
    for (int k = 0; k < 2; ++k) {
      const double den = 1 + d1[k] + d2[k];
      const double n0 = h[k][0], n1 = h[k][1] + d1[k] * h[k][0];
      const double m1 = h[k][1], m2 = h[k][2] + d1[k] * h[k][1];
      area += (n0 + n1) / den + (m1 + m2) / den;
    }
    for (int k = 0; k < 2; ++k) {
      const double den = 1 + d1[k] + d2[k];
      const double n0 = h[k][0] / area, n1 = (h[k][1] + d1[k] * h[k][0]) / area;
      const double m1 = h[k][1] / area, m2 = (h[k][2] + d1[k] * h[k][1]) / area;
      section[k] = {n0, n1, m1, m2, d1[k], d2[k], (n0 + n1) / den, (m1 + m2) / den};
    }
  }
};

// Filters columns [x0, x1) of a row-major image along y, with the recursion in T (float or
// double). All columns of a row are independent, so the inner loops run over x without branches
// and vectorise; rows outside the image are the edge rows (clamp-to-edge) with the recursions at
// their steady state there.
template <typename T, typename Scratch>
[[gnu::always_inline]] inline void deriche_columns(const float* in, float* out, int width,
                                                   int height, int x0, int x1, const Deriche& f,
                                                   Scratch& scratch) {
  const size_t w = size_t(x1 - x0);
  // Causal sums for every row; the state of each section (its last two outputs) stays in cache.
  scratch.resize(size_t(height) * w);
  T* causal = scratch.data();
  std::vector<T> state(4 * w);
  T *p1 = state.data(), *p2 = p1 + w, *q1 = p2 + w, *q2 = q1 + w;
  // Plain local copies in T: stores to the state rows could otherwise alias the coefficients.
  const T sn0 = T(f.section[0].n0), sn1 = T(f.section[0].n1), sm1 = T(f.section[0].m1),
          sm2 = T(f.section[0].m2);
  const T sd1 = T(f.section[0].d1), sd2 = T(f.section[0].d2);
  const T tn0 = T(f.section[1].n0), tn1 = T(f.section[1].n1), tm1 = T(f.section[1].m1),
          tm2 = T(f.section[1].m2);
  const T td1 = T(f.section[1].d1), td2 = T(f.section[1].d2);
  const T s_causal = T(f.section[0].causal_gain), t_causal = T(f.section[1].causal_gain);
  const T s_anticausal = T(f.section[0].anticausal_gain),
          t_anticausal = T(f.section[1].anticausal_gain);
  const float* first = in + x0;
  const float* last = in + size_t(height - 1) * width + x0;
  auto row = [&](int y) { return in + size_t(std::clamp(y, 0, height - 1)) * width + x0; };
  for (size_t i = 0; i < w; ++i) {
    p1[i] = p2[i] = s_causal * first[i];
    q1[i] = q2[i] = t_causal * first[i];
  }
  for (int y = 0; y < height; ++y) {
    const float *x_0 = row(y), *x_1 = row(y - 1);
    T* c = causal + size_t(y) * w;
#pragma GCC ivdep  // the rows never overlap
    for (size_t i = 0; i < w; ++i) {
      const T ys = sn0 * T(x_0[i]) + sn1 * T(x_1[i]) - (sd1 * p1[i] + sd2 * p2[i]);
      const T yt = tn0 * T(x_0[i]) + tn1 * T(x_1[i]) - (td1 * q1[i] + td2 * q2[i]);
      p2[i] = p1[i];
      p1[i] = ys;
      q2[i] = q1[i];
      q1[i] = yt;
      c[i] = ys + yt;
    }
  }
  for (size_t i = 0; i < w; ++i) {
    p1[i] = p2[i] = s_anticausal * last[i];
    q1[i] = q2[i] = t_anticausal * last[i];
  }
  for (int y = height - 1; y >= 0; --y) {
    const float *x_1 = row(y + 1), *x_2 = row(y + 2);
    const T* c = causal + size_t(y) * w;
    float* o = out + size_t(y) * width + x0;
#pragma GCC ivdep
    for (size_t i = 0; i < w; ++i) {
      const T ys = sm1 * T(x_1[i]) + sm2 * T(x_2[i]) - (sd1 * p1[i] + sd2 * p2[i]);
      const T yt = tm1 * T(x_1[i]) + tm2 * T(x_2[i]) - (td1 * q1[i] + td2 * q2[i]);
      p2[i] = p1[i];
      p1[i] = ys;
      q2[i] = q1[i];
      q1[i] = yt;
      o[i] = float(c[i] + (ys + yt));
    }
  }
}

// Scratch for the causal sums, in the recursion's precision (not zero-filled: every value is
// written before it is read).
struct ColumnScratch {
  PixelVector single;
  PixelDoubles twice;
};

// The column filter compiled twice: for AVX2 machines and for the x86-64 baseline, chosen at load
// time (no FMA either way: -ffp-contract=off keeps the bytes the same on every processor).
__attribute__((target_clones("arch=x86-64-v3", "default"))) void filter_columns(
    const float* in, float* out, int width, int height, int x0, int x1, const Deriche& f,
    ColumnScratch& scratch) {
  if (f.in_double)
    deriche_columns<double>(in, out, width, height, x0, x1, f, scratch.twice);
  else
    deriche_columns<float>(in, out, width, height, x0, x1, f, scratch.single);
}

using v8f = float __attribute__((vector_size(32)));

// out[x·out_stride + y] = in[y·in_stride + x] for one 8×8 tile, in registers: three rounds of
// two-source shuffles (neighbouring values, then pairs, then halves). Element by element, the
// strided stores of a transpose cost more than the recursion itself.
[[gnu::always_inline]] inline void transpose_tile8(const float* in, size_t in_stride, float* out,
                                                   size_t out_stride) {
  v8f r[8], a[8], b[8];
  for (int i = 0; i < 8; ++i) std::memcpy(&r[i], in + size_t(i) * in_stride, sizeof(v8f));
  for (int i = 0; i < 8; i += 2) {
    a[i] = __builtin_shufflevector(r[i], r[i + 1], 0, 8, 1, 9, 4, 12, 5, 13);
    a[i + 1] = __builtin_shufflevector(r[i], r[i + 1], 2, 10, 3, 11, 6, 14, 7, 15);
  }
  for (int i = 0; i < 8; i += 4)
    for (int j = 0; j < 2; ++j) {
      b[i + 2 * j] = __builtin_shufflevector(a[i + j], a[i + j + 2], 0, 1, 8, 9, 4, 5, 12, 13);
      b[i + 2 * j + 1] =
          __builtin_shufflevector(a[i + j], a[i + j + 2], 2, 3, 10, 11, 6, 7, 14, 15);
    }
  for (int j = 0; j < 4; ++j) {
    const v8f low = __builtin_shufflevector(b[j], b[j + 4], 0, 1, 2, 3, 8, 9, 10, 11);
    const v8f high = __builtin_shufflevector(b[j], b[j + 4], 4, 5, 6, 7, 12, 13, 14, 15);
    std::memcpy(out + size_t(j) * out_stride, &low, sizeof low);
    std::memcpy(out + size_t(j + 4) * out_stride, &high, sizeof high);
  }
}

// out[x·out_stride + y] = in[y·in_stride + x] for y < rows, x < columns: 8×8 tiles, then the
// right and bottom edges value by value.
__attribute__((target_clones("arch=x86-64-v3", "default"))) void transpose_plane(
    const float* in, size_t in_stride, float* out, size_t out_stride, int rows, int columns) {
  const int rows8 = rows / 8 * 8, columns8 = columns / 8 * 8;
  for (int y = 0; y < rows8; y += 8)
    for (int x = 0; x < columns8; x += 8)
      transpose_tile8(in + size_t(y) * in_stride + size_t(x), in_stride,
                      out + size_t(x) * out_stride + size_t(y), out_stride);
  for (int y = 0; y < rows; ++y)
    for (int x = y < rows8 ? columns8 : 0; x < columns; ++x)
      out[size_t(x) * out_stride + size_t(y)] = in[size_t(y) * in_stride + size_t(x)];
}

void transpose(const float* in, float* out, int width, int height, tbb::task_arena& arena) {
  constexpr int kBlock = 32;
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, (height + kBlock - 1) / kBlock),
                      [&](const tbb::blocked_range<int>& r) {
                        for (int by = r.begin(); by != r.end(); ++by) {
                          const int y0 = by * kBlock;
                          transpose_plane(in + size_t(y0) * width, size_t(width), out + y0,
                                          size_t(height), std::min(kBlock, height - y0), width);
                        }
                      });
  });
}

void recursive_vertical(const float* in, float* out, int width, int height, const Deriche& f,
                        tbb::task_arena& arena) {
  constexpr int kColumns = 256;
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, (width + kColumns - 1) / kColumns),
                      [&](const tbb::blocked_range<int>& r) {
                        ColumnScratch scratch;
                        for (int b = r.begin(); b != r.end(); ++b)
                          filter_columns(in, out, width, height, b * kColumns,
                                         std::min(width, (b + 1) * kColumns), f, scratch);
                      });
  });
}

// Filters every row along x, in place: blocks of 32 rows are transposed (in 8×8 tiles) into a
// small buffer that stays in cache, filtered as columns, and transposed back.
void recursive_horizontal(float* image, int width, int height, const Deriche& f,
                          tbb::task_arena& arena) {
  constexpr int kRows = 32;
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<int>(0, (height + kRows - 1) / kRows),
        [&](const tbb::blocked_range<int>& r) {
          PixelVector block(size_t(width) * kRows), filtered(block.size());  // written before read
          ColumnScratch scratch;
          for (int b = r.begin(); b != r.end(); ++b) {
            int y0 = b * kRows, rows = std::min(kRows, height - y0);
            float* rows_start = image + size_t(y0) * width;
            transpose_plane(rows_start, size_t(width), block.data(), size_t(rows), rows, width);
            filter_columns(block.data(), filtered.data(), rows, width, 0, rows, f, scratch);
            transpose_plane(filtered.data(), size_t(rows), rows_start, size_t(width), width, rows);
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
          for (int k = -radius; k <= radius; ++k)
            sum += kernel[size_t(k + radius)] * src[std::clamp(x + k, 0, width - 1)];
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
  for (int i = -radius; i <= radius; ++i)
    sum += k[size_t(i + radius)] = std::exp(-0.5 * i * i / (sigma * sigma));
  for (double& v : k) v /= sum;
  return k;
}

void check(int width, int height, double sigma) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("gaussian_blur: empty image");
  if (!(sigma > 0) || !std::isfinite(sigma))
    throw std::invalid_argument("gaussian_blur: sigma must be positive");
}

}  // namespace

void gaussian_blur_exact(const float* in, float* out, int width, int height, double sigma,
                         int threads) {
  check(width, height, sigma);
  tbb::task_arena arena(worker_count(threads));
  std::vector<double> kernel = gaussian_kernel(sigma);
  std::vector<float> a(size_t(width) * height), b(a.size());
  fir_rows(in, a.data(), width, height, kernel, arena);
  transpose(a.data(), b.data(), width, height, arena);
  fir_rows(b.data(), a.data(), height, width, kernel, arena);
  transpose(a.data(), out, height, width, arena);
}

void gaussian_blur(const float* in, float* out, int width, int height, double sigma, int threads) {
  check(width, height, sigma);
  if (sigma < kRecursiveMinSigma)
    return gaussian_blur_exact(in, out, width, height, sigma, threads);
  tbb::task_arena arena(worker_count(threads));
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
