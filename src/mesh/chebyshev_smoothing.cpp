#include "mesh/chebyshev_smoothing.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "core/parallel.h"

namespace countershade {
namespace {

// log of c_k for k ≡ n (mod 2), 0 ≤ k ≤ n.
double log_coefficient(int n, int k) {
  const double m = n, j = k;
  const double log_c = (1.0 - m) * std::log(2.0) + std::lgamma(m + 1) -
                       std::lgamma((m - j) / 2 + 1) - std::lgamma((m + j) / 2 + 1);
  return k == 0 ? log_c - std::log(2.0) : log_c;
}

// One step of Clenshaw's recurrence, in place: b2[v] ← c(v)·values[v] + scale·(A·b1)[v] − b2[v],
// with (A·b1)[v] the mean of b1 over v's neighbours (b1[v] itself for a vertex without any).
template <typename T, typename Coefficient>
void clenshaw_step(const VertexAdjacency& adjacency, const std::vector<T>& values,
                   const std::vector<T>& b1, std::vector<T>& b2, double scale, const Coefficient& c,
                   tbb::task_arena& arena) {
  const uint32_t* offsets = adjacency.offsets.data();
  const uint32_t* neighbours = adjacency.neighbours.data();
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, adjacency.vertex_count(), 4096),
                      [&](const tbb::blocked_range<size_t>& r) {
                        for (size_t v = r.begin(); v != r.end(); ++v) {
                          const uint32_t begin = offsets[v], end = offsets[v + 1];
                          T mean = b1[v];
                          if (begin != end) {
                            T sum(0.0);
                            for (uint32_t k = begin; k < end; ++k) sum += b1[neighbours[k]];
                            mean = sum / double(end - begin);
                          }
                          b2[v] = c(v) * values[v] + scale * mean - b2[v];
                        }
                      });
  });
}

}  // namespace

std::vector<double> power_chebyshev_coefficients(int n, double tail) {
  n = std::max(n, 0);
  // The weights peak at k = 0 or 1 and fall like exp(−k²/2n): compute them until they are
  // negligible against the tail, then sum the tail from the far end (small terms first).
  std::vector<double> c(size_t(n) + 1, 0.0);
  int last = n;
  for (int k = n % 2; k <= n; k += 2) {
    c[size_t(k)] = std::exp(log_coefficient(n, k));
    if (c[size_t(k)] < 1e-3 * tail * 1e-3 && k > 0) {
      last = k;
      break;
    }
  }
  double rest = 0;
  int degree = last;
  for (int k = last; k >= 0; --k) {
    if (rest + c[size_t(k)] > tail) break;
    rest += c[size_t(k)];
    degree = k - 1;
  }
  c.resize(size_t(std::max(degree, 0)) + 1);
  return c;
}

namespace {

// chebyshev_smooth for one signal or four side by side (the same numbers in each).
template <typename T>
void clenshaw(const VertexAdjacency& adjacency, const std::vector<uint32_t>& label,
              const std::vector<int>& iterations, std::vector<T>& values, int threads,
              double tail) {
  const size_t count = adjacency.vertex_count();
  std::map<int, std::vector<double>> by_steps;  // one expansion per distinct step count
  size_t degree = 0;
  for (int n : iterations)
    degree = std::max(degree, (by_steps[n] = power_chebyshev_coefficients(n, tail)).size() - 1);
  std::vector<const std::vector<double>*> coefficients(iterations.size());
  for (size_t c = 0; c < iterations.size(); ++c) coefficients[c] = &by_steps.at(iterations[c]);
  const auto c_of = [&](size_t v, size_t k) {
    const std::vector<double>& c = *coefficients[label[v]];
    return k < c.size() ? c[k] : 0.0;
  };
  // Clenshaw: b_k = c_k·v + 2A·b_{k+1} − b_{k+2}; the result is c_0·v + A·b_1 − b_2.
  std::vector<T> b1(count, T(0.0)), b2(count, T(0.0));
  tbb::task_arena arena(worker_count(threads));
  for (size_t k = degree; k >= 1; --k) {
    clenshaw_step(
        adjacency, values, b1, b2, 2.0, [&](size_t v) { return c_of(v, k); }, arena);
    b1.swap(b2);  // b1 = b_k, b2 = b_{k+1}
  }
  clenshaw_step(
      adjacency, values, b1, b2, 1.0, [&](size_t v) { return c_of(v, 0); }, arena);
  values.swap(b2);
}

}  // namespace

void chebyshev_smooth(const VertexAdjacency& adjacency, const std::vector<uint32_t>& label,
                      const std::vector<int>& iterations, std::vector<double>& values, int threads,
                      double tail) {
  clenshaw(adjacency, label, iterations, values, threads, tail);
}

void chebyshev_smooth(const VertexAdjacency& adjacency, const std::vector<uint32_t>& label,
                      const std::vector<int>& iterations, std::vector<glm::dvec4>& values,
                      int threads, double tail) {
  clenshaw(adjacency, label, iterations, values, threads, tail);
}

}  // namespace countershade
