// Levenberg–Marquardt for the analysis's small least-squares problems (two or three parameters,
// tens of residuals) within a box of bounds. Derivatives come from automatic differentiation
// (Ceres' header-only Jets), so a problem is written once, as a template over the number type.
// A parameter on a bound stays there while the gradient points out of the box (an active set);
// the others take damped Gauss–Newton steps, clamped to the box.

#pragma once

#include <ceres/jet.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

namespace countershade::analysis {

template <int N>
using ParameterVector = Eigen::Matrix<double, N, 1>;

template <int N>
struct ParameterBox {
  ParameterVector<N> lower, upper;
};

struct LeastSquaresResult {
  double sum_of_squares = 0;  // at the returned parameters
  bool finite = false;        // false when the residuals could not be evaluated (NaN or ∞)
};

// `Residuals` has `int count() const` and `template <class T> void operator()(const T* p, T* r)
// const`, which writes count() residuals at p.
template <int N, class Residuals>
double sum_of_squares(const Residuals& residuals, const ParameterVector<N>& p) {
  std::vector<double> r(size_t(residuals.count()));
  residuals(p.data(), r.data());
  double sum = 0;
  for (double x : r) sum += x * x;
  return sum;
}

namespace detail {

// The Gauss–Newton normal equations at p: JᵀJ and the gradient Jᵀr, summed residual by residual
// (fixed-size products: dynamic-size Eigen products would instantiate its matrix kernels).
template <int N>
struct NormalEquations {
  Eigen::Matrix<double, N, N> normal = Eigen::Matrix<double, N, N>::Zero();
  ParameterVector<N> gradient = ParameterVector<N>::Zero();
};

template <int N, class Residuals>
NormalEquations<N> linearize(const Residuals& residuals, const ParameterVector<N>& p) {
  using Jet = ceres::Jet<double, N>;
  Jet q[N];
  for (int i = 0; i < N; ++i) q[i] = Jet(p[i], i);
  std::vector<Jet> out(size_t(residuals.count()));
  residuals(q, out.data());
  NormalEquations<N> e;
  for (const Jet& r : out) {
    e.normal += r.v * r.v.transpose();
    e.gradient += r.v * r.a;
  }
  return e;
}

// The damped Gauss–Newton step from p with the parameters held by a bound left out, clamped to
// the box.
template <int N>
ParameterVector<N> box_step(const NormalEquations<N>& e, const ParameterBox<N>& box,
                            const ParameterVector<N>& p, double damping) {
  Eigen::Matrix<double, N, N> normal = e.normal;
  ParameterVector<N> rhs = -e.gradient;
  for (int i = 0; i < N; ++i) {
    const bool held =
        (p[i] <= box.lower[i] && e.gradient[i] > 0) || (p[i] >= box.upper[i] && e.gradient[i] < 0);
    if (held) {
      normal.row(i).setZero(), normal.col(i).setZero();
      normal(i, i) = 1, rhs[i] = 0;
    } else {
      normal(i, i) *= 1 + damping;
    }
  }
  const ParameterVector<N> step = normal.ldlt().solve(rhs);
  return (p + step).cwiseMax(box.lower).cwiseMin(box.upper);
}

}  // namespace detail

// Minimises the sum of squares of `residuals` over the box from p (clamped into it), in place. It
// stops when a step no longer lowers the sum (to 1e-16 of it) or moves the parameters, or when
// no damping finds a lower sum. Near the optimum the sum changes with the square of the step, so
// the parameters are found to about 1e-8 of the scale on which the sum doubles, not to double
// precision: a caller that needs more polishes with Newton steps (analysis/fit.cpp does).
template <int N, class Residuals>
LeastSquaresResult minimize_within_box(const Residuals& residuals, const ParameterBox<N>& box,
                                       ParameterVector<N>& p, int max_iterations = 500) {
  p = p.cwiseMax(box.lower).cwiseMin(box.upper);
  double sum = sum_of_squares<N>(residuals, p), damping = 1e-3;
  detail::NormalEquations<N> equations;
  bool linearized = false;
  for (int iteration = 0; iteration < max_iterations && damping < 1e12; ++iteration) {
    if (!linearized) equations = detail::linearize<N>(residuals, p), linearized = true;
    const ParameterVector<N> next = detail::box_step<N>(equations, box, p, damping);
    const double next_sum = sum_of_squares<N>(residuals, next);
    if (!(next_sum <= sum)) {
      damping *= 4;
      continue;
    }
    const bool still = next == p || sum - next_sum <= 1e-16 * sum;
    p = next, sum = next_sum, linearized = false;
    damping = std::max(1e-12, damping / 3);
    if (still) break;
  }
  return {sum, std::isfinite(sum)};
}

}  // namespace countershade::analysis
