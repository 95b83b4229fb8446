#include "analysis/fit.h"

#include <tbb/parallel_for.h>

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/special_functions/erf.hpp>
#include <cmath>
#include <map>
#include <numbers>
#include <optional>

#include "analysis/bounded_least_squares.h"
#include "core/error.h"
#include "core/random.h"

namespace countershade::analysis {
namespace {

// Unqualified math so Ceres Jets work (see the Ceres examples).
using std::erfc;
using std::exp;
using std::log;

// Standard cumulative distribution of the model's reduced variable z.
template <class T>
T standard_cdf(ThresholdModel model, const T& z) {
  switch (model) {
    case ThresholdModel::log_normal:
      return T(0.5) * erfc(-z / T(std::numbers::sqrt2));
    case ThresholdModel::weibull:
      return T(1.0) - exp(-exp(z));  // minimum extreme value
    case ThresholdModel::logistic:
    case ThresholdModel::log_logistic:
      return T(1.0) / (T(1.0) + exp(-z));
  }
  return z;
}

// Reduced variable of λ; every model but the logistic works on ln λ, the logistic on λ itself.
template <class T>
T reduced(ThresholdModel model, double lambda, const T& location, const T& log_scale) {
  T x = model == ThresholdModel::logistic ? T(lambda) : T(std::log(lambda));
  return (x - location) / exp(log_scale);
}

// The model's survival function 1 − F of the reduced variable, computed directly so that a far
// right tail keeps its precision.
template <class T>
T standard_survival(ThresholdModel model, const T& z) {
  switch (model) {
    case ThresholdModel::log_normal:
      return T(0.5) * erfc(z / T(std::numbers::sqrt2));
    case ThresholdModel::weibull:
      return exp(-exp(z));
    case ThresholdModel::logistic:
    case ThresholdModel::log_logistic:
      return T(1.0) / (T(1.0) + exp(z));
  }
  return z;
}

// The probability of one answer's interval (lower, upper]: F(upper) − F(lower), with F(0) = 0
// for every model (left-censoring) and F(∞) = 1 (right-censoring).
template <class T>
T interval_probability(ThresholdModel model, const AnswerInterval& a, const T& location,
                       const T& log_scale) {
  const bool left = !(a.lower > 0), right = std::isinf(a.upper);
  if (left && right) return T(1.0);
  if (right) return standard_survival(model, reduced(model, a.lower, location, log_scale));
  const T upper = standard_cdf(model, reduced(model, a.upper, location, log_scale));
  if (left) return upper;
  return upper - standard_cdf(model, reduced(model, a.lower, location, log_scale));
}

using AnswerCounts = std::map<AnswerInterval, double>;

// Every distinct interval with its count: residual √(2·count·(−ln P)), so the sum of squares is
// −2 ln L and its minimum is the maximum-likelihood estimate.
struct AnswerResiduals {
  ThresholdModel model;
  std::vector<std::pair<AnswerInterval, double>> counts;
  int count() const { return int(counts.size()); }
  template <class T>
  void operator()(const T* params, T* residuals) const {
    using std::sqrt;
    for (size_t i = 0; i < counts.size(); ++i) {
      T p = interval_probability(model, counts[i].first, params[0], params[1]);
      if (!(p > T(1e-300))) p = T(1e-300);
      residuals[i] = sqrt(T(2.0 * counts[i].second) * -log(p) + T(1e-300));
    }
  }
};

double negative_log_likelihood(ThresholdModel model, const AnswerCounts& counts, const double* q) {
  double nll = 0;
  for (const auto& [interval, count] : counts)
    nll -= count * std::log(std::max(1e-300, interval_probability(model, interval, q[0], q[1])));
  return nll;
}

// Gradient of −ln L by automatic differentiation.
Eigen::Vector2d gradient(ThresholdModel model, const AnswerCounts& counts, const double* q) {
  using J = ceres::Jet<double, 2>;
  J location(q[0], 0), log_scale(q[1], 1), nll(0.0);
  for (const auto& [interval, count] : counts)
    nll -= J(count) * log(interval_probability(model, interval, location, log_scale));
  return {nll.v[0], nll.v[1]};
}

// The observed information: the Hessian of −ln L, by central differences of the exact gradient.
Eigen::Matrix2d hessian(ThresholdModel model, const AnswerCounts& counts, const double* q) {
  Eigen::Matrix2d h;
  for (int k = 0; k < 2; ++k) {
    double e = 1e-5 * std::max(1.0, std::abs(q[k]));
    double plus[2] = {q[0], q[1]}, minus[2] = {q[0], q[1]};
    plus[k] += e;
    minus[k] -= e;
    h.col(k) = (gradient(model, counts, plus) - gradient(model, counts, minus)) / (2 * e);
  }
  return 0.5 * (h + h.transpose());
}

// An interval's end on the model's scale, for bounds and starting values: its upper end, or its
// lower end when it is open above.
double model_scale_point(ThresholdModel model, const AnswerInterval& a) {
  const double x = std::isinf(a.upper) ? a.lower : a.upper;
  return model == ThresholdModel::logistic ? x : std::log(x);
}

// The narrowest closed interval: the grid step, the natural unit of the logistic's scale. When
// every answer is open above, `fallback`.
double narrowest_interval(const AnswerCounts& counts, double fallback) {
  double narrowest = std::numeric_limits<double>::infinity();
  for (const auto& [interval, count] : counts)
    if (!std::isinf(interval.upper))
      narrowest = std::min(narrowest, interval.upper - interval.lower);
  return std::isinf(narrowest) ? fallback : narrowest;
}

// Minimises −ln L within bounds around the answers; returns whether the solution is usable.
bool minimize(ThresholdModel model, const AnswerCounts& counts, double* q) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& [interval, count] : counts) {
    const double x = model_scale_point(model, interval);
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  const double narrowest = narrowest_interval(counts, std::exp(lo));
  const ParameterBox<2> box{
      {lo - 10.0, std::log(1e-4 * (model == ThresholdModel::logistic ? narrowest : 1.0))},
      {hi + 10.0, std::log(100.0 * std::max(1.0, hi - lo + 1.0))}};
  ParameterVector<2> p(q[0], q[1]);
  const AnswerResiduals residuals{model, {counts.begin(), counts.end()}};
  const bool usable = minimize_within_box<2>(residuals, box, p).finite;
  q[0] = p[0], q[1] = p[1];
  return usable;
}

// Newton steps on the exact likelihood: the Gauss–Newton model of the square-root residuals
// converges slowly near the optimum.
void polish(ThresholdModel model, const AnswerCounts& counts, double* q) {
  for (int it = 0; it < 20; ++it) {
    Eigen::Vector2d g = gradient(model, counts, q);
    Eigen::Matrix2d h = hessian(model, counts, q);
    if (h.determinant() <= 0) break;
    Eigen::Vector2d dq = h.ldlt().solve(g);
    double base = negative_log_likelihood(model, counts, q), t = 1.0;
    double next[2];
    for (int tries = 0; tries < 30; ++tries, t *= 0.5) {
      next[0] = q[0] - t * dq[0];
      next[1] = q[1] - t * dq[1];
      if (negative_log_likelihood(model, counts, next) <= base + 1e-12) break;
    }
    q[0] = next[0];
    q[1] = next[1];
    if (dq.norm() * t < 1e-12) break;
  }
}

// The log-threshold (the log-median) and its gradient with respect to (μ, ln σ), for the delta
// method.
std::pair<double, Eigen::Vector2d> log_median(ThresholdModel model, double location, double scale) {
  switch (model) {
    case ThresholdModel::log_normal:
    case ThresholdModel::log_logistic:
      return {location, {1.0, 0.0}};
    case ThresholdModel::weibull: {  // median = exp(μ + σ ln ln 2)
      const double c = std::log(std::log(2.0));
      return {location + scale * c, {1.0, scale * c}};
    }
    case ThresholdModel::logistic: {  // median = μ on the λ scale
      const double mu = std::max(location, 1e-300);
      return {std::log(mu), {1.0 / mu, 0.0}};
    }
  }
  return {location, {1.0, 0.0}};
}

// The grid boundary every answer touches, when there is one: all answers in one step (its top), or
// split between the two steps on either side of one boundary. The likelihood then grows without
// end as the spread shrinks to 0 at that boundary, so the spread and the threshold's standard
// error are not identified; the threshold is the boundary (the step answered).
std::optional<double> collapsed_boundary(const AnswerCounts& counts) {
  for (const auto& [candidate, unused] : counts) {
    const double b = candidate.upper;
    if (!std::isfinite(b)) continue;
    const bool all = std::all_of(counts.begin(), counts.end(), [b](const auto& entry) {
      return entry.first.upper == b || entry.first.lower == b;
    });
    if (all) return b;
  }
  return std::nullopt;
}

Fit solve(const AnswerCounts& counts, ThresholdModel model, const double* start) {
  double q[2] = {start[0], start[1]};
  const bool usable = minimize(model, counts, q);
  polish(model, counts, q);
  Fit fit;
  fit.model = model;
  fit.location = q[0];
  fit.scale = std::exp(q[1]);
  for (const auto& [interval, count] : counts) {
    fit.n += size_t(count);
    fit.left_censored += !(interval.lower > 0) ? size_t(count) : 0;
    fit.right_censored += std::isinf(interval.upper) ? size_t(count) : 0;
  }
  fit.identified = fit.left_censored < fit.n && fit.right_censored < fit.n;
  const Eigen::Matrix2d h = hessian(model, counts, q);
  const bool positive = h.determinant() > 0 && h(0, 0) > 0;
  fit.converged = fit.identified && usable && positive &&
                  gradient(model, counts, q).norm() < 1e-4 * std::max(1.0, double(fit.n));
  const Eigen::Matrix2d covariance =
      positive ? Eigen::Matrix2d(h.inverse()) : Eigen::Matrix2d::Constant(std::nan(""));
  fit.location_se = std::sqrt(covariance(0, 0));
  const auto [log_threshold, d] = log_median(model, fit.location, fit.scale);
  fit.log_threshold = log_threshold;
  fit.log_threshold_se = std::sqrt(d.dot(covariance * d));
  fit.threshold = std::exp(fit.log_threshold);
  if (const auto boundary = fit.identified ? collapsed_boundary(counts) : std::nullopt;
      boundary && *boundary > 0) {
    fit.identified = fit.converged = false;
    fit.one_step = true;
    fit.threshold = *boundary;
    fit.log_threshold = std::log(*boundary);
  }
  if (!fit.identified) fit.location_se = fit.log_threshold_se = std::nan("");
  return fit;
}

AnswerCounts count_answers(const std::vector<AnswerInterval>& answers) {
  AnswerCounts counts;
  for (const auto& a : answers) counts[a] += 1.0;
  return counts;
}

// A threshold drawn from the fitted model, by its inverse CDF.
double draw_threshold(const Fit& fit, SampleStream& random) {
  const double u = std::clamp(random.next(), 1e-12, 1.0 - 1e-12);
  double z;
  switch (fit.model) {
    case ThresholdModel::log_normal:
      z = -std::numbers::sqrt2 * boost::math::erfc_inv(2.0 * u);
      break;
    case ThresholdModel::weibull:
      z = std::log(-std::log(1.0 - u));
      break;
    default:
      z = std::log(u / (1.0 - u));
  }
  const double v = fit.location + fit.scale * z;
  return fit.model == ThresholdModel::logistic ? v : std::exp(v);
}

// The answer an observer with threshold t gives on the grid: the first value at or above t, at
// most the top.
AnswerInterval grid_answer(const AnswerGrid& grid, double t) {
  int index = std::max(0, int(std::ceil(std::min((t - grid.first) / grid.step, 1e9) - 1e-9)));
  double lambda = grid.first + index * grid.step;
  if (lambda >= grid.top - 1e-9 * grid.step) {
    index = int(std::lround((grid.top - grid.first) / grid.step));
    lambda = grid.top;
  }
  return answer_interval(lambda, index, grid.step, std::isinf(grid.top) ? 0.0 : grid.top);
}

}  // namespace

AnswerInterval answer_interval(double lambda, int index, double step, double top, bool* zero) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  const double tolerance = 1e-9 * step;
  if (zero) *zero = lambda <= tolerance;
  if (lambda <= tolerance) return {0.0, step};  // (0, λ_1] on a grid that starts at 0
  AnswerInterval a{lambda - step, lambda};
  if (index == 0 || a.lower <= tolerance) a.lower = 0.0;
  if (top > 0 && lambda >= top - tolerance) a.upper = kInfinity;
  return a;
}

Fit fit_threshold(const std::vector<AnswerInterval>& answers, ThresholdModel model) {
  if (answers.empty()) throw InputError("a threshold fit needs at least one answer");
  // Start from the moments of the answers on the model's scale.
  double sum = 0, sq = 0, n = 0;
  for (const auto& a : answers) {
    const double x = model_scale_point(model, a);
    sum += x;
    sq += x * x;
    n += 1;
  }
  const AnswerCounts counts = count_answers(answers);
  const double mean = sum / n, sd = std::sqrt(std::max(sq / n - mean * mean, 0.0));
  const double start[2] = {
      mean, std::log(std::max(
                sd, model == ThresholdModel::logistic ? narrowest_interval(counts, 1.0) : 0.05))};
  return solve(counts, model, start);
}

double fit_cdf(const Fit& fit, double lambda) {
  if (lambda <= 0) return 0.0;
  double x = fit.model == ThresholdModel::logistic ? lambda : std::log(lambda);
  return standard_cdf(fit.model, (x - fit.location) / fit.scale);
}

void bootstrap_threshold(Fit& fit, const AnswerGrid& grid, int resamples, uint64_t seed) {
  // A model whose parameters ran off to infinity draws no thresholds (found by the fuzzer: NaN
  // draws became grid indices); its fit is reported as not converged already.
  if (!std::isfinite(fit.location) || !std::isfinite(fit.scale) || !(fit.scale > 0)) return;
  const double start[2] = {fit.location, std::log(fit.scale)};
  // Each resample has its own random stream, so the result does not depend on scheduling.
  std::vector<double> results(size_t(resamples), std::nan(""));
  tbb::parallel_for(0, resamples, [&](int b) {
    std::vector<AnswerInterval> sample(fit.n);
    SampleStream random(seed, 5, uint64_t(b), 0);
    for (auto& a : sample) a = grid_answer(grid, draw_threshold(fit, random));
    Fit refit = solve(count_answers(sample), fit.model, start);
    if (refit.converged) results[size_t(b)] = refit.threshold;
  });
  std::vector<double> thresholds;
  for (double t : results)
    if (!std::isnan(t)) thresholds.push_back(t);
  fit.bootstrap = int(thresholds.size());
  if (thresholds.size() < 2) return;
  std::sort(thresholds.begin(), thresholds.end());
  auto quantile = [&](double p) {  // R's type 7
    double h = (double(thresholds.size()) - 1.0) * p;
    size_t i = size_t(std::floor(h));
    double frac = h - double(i);
    return i + 1 < thresholds.size() ? thresholds[i] + frac * (thresholds[i + 1] - thresholds[i])
                                     : thresholds[i];
  };
  fit.ci_low = quantile(0.025);
  fit.ci_high = quantile(0.975);
}

}  // namespace countershade::analysis
