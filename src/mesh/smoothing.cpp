#include "mesh/smoothing.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <sstream>

#include "core/error.h"
#include "core/parallel.h"
#include "mesh/chebyshev_smoothing.h"
#include "mesh/vertex_order.h"

namespace countershade {

int iterations_for_sigma(double sigma, double mean_edge_length) {
  if (!(mean_edge_length > 0)) return 1;
  const double n = std::round(2.0 * sigma * sigma / (mean_edge_length * mean_edge_length));
  if (!(n <= kMaxSmoothingIterations)) {
    std::ostringstream what;
    what << "sigma = " << sigma << " needs " << n
         << " smoothing iterations on a mesh whose edges average " << mean_edge_length
         << "; the limit is " << kMaxSmoothingIterations
         << " (use a smaller sigma, or --refine a coarse mesh less finely)";
    throw InputError(what.str());
  }
  return int(std::max(n, 1.0));
}

namespace {

// laplacian_smooth for one signal or four side by side (the same numbers in each).
template <typename T>
void laplacian_steps(const VertexAdjacency& adjacency, const std::vector<uint32_t>& label,
                     const std::vector<int>& iterations, std::vector<T>& values, int threads) {
  const size_t n = adjacency.vertex_count();
  int most = 0;
  for (int it : iterations) most = std::max(most, it);
  std::vector<T> next(values);
  const uint32_t* offsets = adjacency.offsets.data();
  const uint32_t* neighbours = adjacency.neighbours.data();
  tbb::task_arena arena(worker_count(threads));
  for (int step = 0; step < most; ++step) {
    const T* src = values.data();
    T* dst = next.data();
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 4096),
                        [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t v = r.begin(); v != r.end(); ++v) {
                            uint32_t begin = offsets[v], end = offsets[v + 1];
                            if (begin == end || step >= iterations[label[v]]) {
                              dst[v] = src[v];
                              continue;
                            }
                            T sum(0.0);
                            for (uint32_t k = begin; k < end; ++k) sum += src[neighbours[k]];
                            dst[v] = sum / double(end - begin);
                          }
                        });
    });
    values.swap(next);
  }
}

}  // namespace

void laplacian_smooth(const VertexAdjacency& adjacency, const std::vector<uint32_t>& label,
                      const std::vector<int>& iterations, std::vector<double>& values,
                      int threads) {
  laplacian_steps(adjacency, label, iterations, values, threads);
}

namespace {

// Whether the truncated expansion takes fewer products than the steps themselves, `most` being the
// most steps any component takes (the degree grows with the steps): degree K costs K + 1 products,
// so below about 22 steps, where nothing is truncated (K = n), the plain steps compute the same
// operator more cheaply.
bool expansion_pays(int most) { return power_chebyshev_coefficients(most).size() < size_t(most); }

template <typename T>
void smooth_in_given_order(const VertexAdjacency& adjacency, const std::vector<uint32_t>& label,
                           const std::vector<int>& iterations, int most, std::vector<T>& values,
                           SmoothingScheme scheme, int threads) {
  if (scheme == SmoothingScheme::chebyshev && expansion_pays(most))
    return chebyshev_smooth(adjacency, label, iterations, values, threads);
  laplacian_steps(adjacency, label, iterations, values, threads);
}

template <typename T>
void smooth_signals(const VertexAdjacency& adjacency, const std::vector<uint32_t>& label,
                    const std::vector<int>& iterations, std::vector<T>& values,
                    SmoothingScheme scheme, int threads) {
  const int most = iterations.empty() ? 0 : *std::max_element(iterations.begin(), iterations.end());
  if (adjacency.vertex_count() <= kReorderAbove || most < kReorderSteps)
    return smooth_in_given_order(adjacency, label, iterations, most, values, scheme, threads);
  const std::vector<uint32_t> order = breadth_first_order(adjacency);
  std::vector<T> local = gathered(values, order);
  smooth_in_given_order(renumbered(adjacency, order), gathered(label, order), iterations, most,
                        local, scheme, threads);
  scatter(local, order, values);
}

}  // namespace

void smooth_over_rings(const VertexAdjacency& adjacency, const std::vector<uint32_t>& label,
                       const std::vector<int>& iterations, std::vector<double>& values,
                       SmoothingScheme scheme, int threads) {
  smooth_signals(adjacency, label, iterations, values, scheme, threads);
}

void smooth_over_rings(const VertexAdjacency& adjacency, const std::vector<uint32_t>& label,
                       const std::vector<int>& iterations, std::vector<glm::dvec4>& values,
                       SmoothingScheme scheme, int threads) {
  smooth_signals(adjacency, label, iterations, values, scheme, threads);
}

std::vector<double> one_ring_variance(const VertexAdjacency& adjacency,
                                      const std::vector<double>& values, int threads) {
  std::vector<double> variance(adjacency.vertex_count(), 0.0);
  parallel_ranges(
      variance.size(), threads,
      [&](size_t begin, size_t end) {
        for (size_t v = begin; v < end; ++v) {
          auto ring = adjacency.of(v);
          double count = double(ring.size() + 1), mean = values[v];
          for (uint32_t w : ring) mean += values[w];
          mean /= count;
          double sq = (values[v] - mean) * (values[v] - mean);
          for (uint32_t w : ring) sq += (values[w] - mean) * (values[w] - mean);
          variance[v] = sq / count;
        }
      },
      4096);
  return variance;
}

std::vector<double> component_mean_edge_length(const std::vector<glm::vec3>& positions,
                                               const VertexAdjacency& adjacency,
                                               const Components& components) {
  std::vector<double> sum(components.count, 0.0), count(components.count, 0.0);
  for (size_t v = 0; v < adjacency.vertex_count(); ++v)
    for (uint32_t w : adjacency.of(v)) {
      if (w <= v) continue;  // each undirected edge once
      uint32_t c = components.label[v];
      sum[c] += glm::length(glm::dvec3(positions[v]) - glm::dvec3(positions[w]));
      count[c] += 1.0;
    }
  for (uint32_t c = 0; c < components.count; ++c) sum[c] = count[c] > 0 ? sum[c] / count[c] : 0.0;
  return sum;
}

}  // namespace countershade
