#pragma once
// n steps of the 1-ring average A (mesh/smoothing.h) in O(√n) products: A^n v approximated by
// the Chebyshev expansion of x^n truncated where its tail falls below ε. A is similar to a
// symmetric matrix with its spectrum in [−1, 1], so with x^n = Σ_k c_k T_k(x) (c_k ≥ 0, the
// binomial weights c_k = 2^(1−n)·C(n, (n−k)/2) for k ≡ n mod 2, half that for k = 0) and
// |T_k| ≤ 1 there, dropping the terms k > K costs at most Σ_{k>K} c_k ≤ ε of the signal's range.
// Those weights spread over k like a Gaussian of width √n, so K ≈ √(2n·ln(2/ε)).

#include <cstdint>
#include <glm/vec4.hpp>
#include <vector>

#include "mesh/adjacency.h"

namespace countershade {

// The default tail: 1e-7 of the signal's range, far below both an 8-bit level and the 1e-4 the
// iterations are matched to.
inline constexpr double kChebyshevTail = 1e-7;

// The coefficients c_0 … c_K of x^n's expansion, K the smallest degree whose tail is ≤ `tail`.
std::vector<double> power_chebyshev_coefficients(int n, double tail = kChebyshevTail);

// What laplacian_smooth does (each component its own count of steps, vertices without neighbours
// kept), by the truncated expansion: one product with A per degree, evaluated with Clenshaw's
// recurrence. Deterministic: each vertex's sums run in a fixed order whatever the threads.
void chebyshev_smooth(const VertexAdjacency& adjacency, const std::vector<uint32_t>& label,
                      const std::vector<int>& iterations, std::vector<double>& values,
                      int threads = 0, double tail = kChebyshevTail);
// Four signals at once: the same numbers as four calls, in one pass over the rings.
void chebyshev_smooth(const VertexAdjacency& adjacency, const std::vector<uint32_t>& label,
                      const std::vector<int>& iterations, std::vector<glm::dvec4>& values,
                      int threads = 0, double tail = kChebyshevTail);

}  // namespace countershade
