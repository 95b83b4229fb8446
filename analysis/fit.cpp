#include "analysis/fit.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include <boost/math/special_functions/erf.hpp>
#include <ceres/ceres.h>
#include <glog/logging.h>
#include <tbb/parallel_for.h>
#include <Eigen/Dense>

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
T standard_cdf(FitModel model, const T& z) {
  switch (model) {
    case FitModel::lognormal: return T(0.5) * erfc(-z / T(std::numbers::sqrt2));
    case FitModel::weibull: return T(1.0) - exp(-exp(z));  // minimum extreme value
    case FitModel::logistic: return T(1.0) / (T(1.0) + exp(-z));
  }
  return z;
}

// Reduced variable of λ; lognormal and Weibull work on ln λ, logistic on λ itself.
template <class T>
T reduced(FitModel model, double lambda, const T& location, const T& log_scale) {
  T x = model == FitModel::logistic ? T(lambda) : T(std::log(lambda));
  return (x - location) / exp(log_scale);
}

// The probability of one grid answer: the interval (λ − step, λ], or (0, λ] at the first step.
template <class T>
T interval_probability(FitModel model, double lambda, double step, const T& location, const T& log_scale) {
  double upper = std::max(lambda, step);
  T p_upper = standard_cdf(model, reduced(model, upper, location, log_scale));
  double lower = upper - step;
  if (lower <= 1e-9 * step) {
    if (model != FitModel::logistic) return p_upper;  // left-censored: F(0) = 0 on a log scale
    return p_upper - standard_cdf(model, (T(0.0) - location) / exp(log_scale));
  }
  return p_upper - standard_cdf(model, reduced(model, lower, location, log_scale));
}

// One distinct answer value with its count: residual √(2·count·(−ln P)), so the sum of squares is
// −2 ln L and Ceres' minimum is the maximum-likelihood estimate.
struct AnswerResidual {
  AnswerResidual(FitModel model, double lambda, double step, double count)
      : model(model), lambda(lambda), step(step), count(count) {}
  template <class T>
  bool operator()(const T* const params, T* residual) const {
    T p = interval_probability(model, lambda, step, params[0], params[1]);
    if (!(p > T(1e-300))) p = T(1e-300);
    residual[0] = sqrt(T(2.0 * count) * -log(p) + T(1e-300));
    return true;
  }
  FitModel model;
  double lambda, step, count;
};

double negative_log_likelihood(FitModel model, const std::map<double, double>& counts, double step, const double* q) {
  double nll = 0;
  for (const auto& [lambda, count] : counts)
    nll -= count * std::log(std::max(1e-300, interval_probability(model, lambda, step, q[0], q[1])));
  return nll;
}

// Gradient of −ln L by automatic differentiation.
Eigen::Vector2d gradient(FitModel model, const std::map<double, double>& counts, double step, const double* q) {
  using J = ceres::Jet<double, 2>;
  J location(q[0], 0), log_scale(q[1], 1), nll(0.0);
  for (const auto& [lambda, count] : counts) nll -= J(count) * log(interval_probability(model, lambda, step, location, log_scale));
  return {nll.v[0], nll.v[1]};
}

// The observed information: the Hessian of −ln L, by central differences of the exact gradient.
Eigen::Matrix2d hessian(FitModel model, const std::map<double, double>& counts, double step, const double* q) {
  Eigen::Matrix2d h;
  for (int k = 0; k < 2; ++k) {
    double e = 1e-5 * std::max(1.0, std::abs(q[k]));
    double plus[2] = {q[0], q[1]}, minus[2] = {q[0], q[1]};
    plus[k] += e;
    minus[k] -= e;
    h.col(k) = (gradient(model, counts, step, plus) - gradient(model, counts, step, minus)) / (2 * e);
  }
  return 0.5 * (h + h.transpose());
}

Fit solve(const std::map<double, double>& counts, double step, FitModel model, const double* start) {
  double q[2] = {start[0], start[1]};
  ceres::Problem problem;
  for (const auto& [lambda, count] : counts)
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<AnswerResidual, 1, 2>(
                                 new AnswerResidual(model, lambda, step, count)),
                             nullptr, q);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& [lambda, count] : counts) {
    double x = model == FitModel::logistic ? std::max(lambda, step) : std::log(std::max(lambda, step));
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  problem.SetParameterLowerBound(q, 0, lo - 10.0);
  problem.SetParameterUpperBound(q, 0, hi + 10.0);
  problem.SetParameterLowerBound(q, 1, std::log(1e-4 * (model == FitModel::logistic ? step : 1.0)));
  problem.SetParameterUpperBound(q, 1, std::log(100.0 * std::max(1.0, hi - lo + 1.0)));
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 200;
  options.function_tolerance = 1e-16;
  options.gradient_tolerance = 1e-16;
  options.parameter_tolerance = 1e-14;
  options.logging_type = ceres::SILENT;
  options.num_threads = 1;
  // Ceres reports a stalled minimiser through glog's ERROR log even when silent; the fit's
  // `converged` flag already records it, so only fatal messages may reach the terminal.
  static const bool quiet = [] {
    FLAGS_minloglevel = google::GLOG_FATAL;
    return true;
  }();
  (void)quiet;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);

  // Polish with Newton steps on the exact likelihood: the Gauss–Newton model of the square-root
  // residuals converges slowly near the optimum.
  for (int it = 0; it < 20; ++it) {
    Eigen::Vector2d g = gradient(model, counts, step, q);
    Eigen::Matrix2d h = hessian(model, counts, step, q);
    if (h.determinant() <= 0) break;
    Eigen::Vector2d dq = h.ldlt().solve(g);
    double base = negative_log_likelihood(model, counts, step, q), t = 1.0;
    double next[2];
    for (int tries = 0; tries < 30; ++tries, t *= 0.5) {
      next[0] = q[0] - t * dq[0];
      next[1] = q[1] - t * dq[1];
      if (negative_log_likelihood(model, counts, step, next) <= base + 1e-12) break;
    }
    q[0] = next[0];
    q[1] = next[1];
    if (dq.norm() * t < 1e-12) break;
  }

  Fit fit;
  fit.model = model;
  fit.location = q[0];
  fit.scale = std::exp(q[1]);
  for (const auto& [lambda, count] : counts) fit.n += size_t(count);
  Eigen::Matrix2d h = hessian(model, counts, step, q);
  fit.converged = summary.IsSolutionUsable() && h.determinant() > 0 && gradient(model, counts, step, q).norm() < 1e-4 * std::max(1.0, double(fit.n));
  fit.location_se = h.determinant() > 0 ? std::sqrt(h.inverse()(0, 0)) : std::nan("");
  switch (model) {
    case FitModel::lognormal:
      fit.log_threshold = fit.location;
      fit.log_threshold_se = fit.location_se;
      break;
    case FitModel::weibull:  // median = exp(μ + σ ln ln 2); SE reported for μ
      fit.log_threshold = fit.location + fit.scale * std::log(std::log(2.0));
      fit.log_threshold_se = fit.location_se;
      break;
    case FitModel::logistic:  // median = μ on the λ scale; delta method for ln μ
      fit.log_threshold = std::log(std::max(fit.location, 1e-300));
      fit.log_threshold_se = fit.location_se / std::max(fit.location, 1e-300);
      break;
  }
  fit.threshold = std::exp(fit.log_threshold);
  return fit;
}

std::map<double, double> count_answers(const std::vector<double>& answers, double step) {
  std::map<double, double> counts;
  for (double a : answers) counts[std::round(a / step) * step] += 1.0;  // snap to the grid
  return counts;
}

}  // namespace

FitModel parse_fit_model(const std::string& name) {
  if (name == "lognormal") return FitModel::lognormal;
  if (name == "weibull") return FitModel::weibull;
  if (name == "logistic") return FitModel::logistic;
  throw InputError("--model: unknown model '" + name + "' (expected lognormal, weibull or logistic)");
}

const char* fit_model_name(FitModel model) {
  switch (model) {
    case FitModel::lognormal: return "lognormal";
    case FitModel::weibull: return "weibull";
    case FitModel::logistic: return "logistic";
  }
  return "?";
}

Fit fit_threshold(const std::vector<double>& answers, double step, FitModel model) {
  auto counts = count_answers(answers, step);
  // Start from the moments of the answers on the model's scale.
  double sum = 0, sq = 0, n = 0;
  for (double a : answers) {
    double x = model == FitModel::logistic ? std::max(a, step) : std::log(std::max(a, step));
    sum += x;
    sq += x * x;
    n += 1;
  }
  double mean = sum / n, sd = std::sqrt(std::max(sq / n - mean * mean, 0.0));
  double start[2] = {mean, std::log(std::max(sd, model == FitModel::logistic ? step : 0.05))};
  return solve(counts, step, model, start);
}

double fit_cdf(const Fit& fit, double lambda) {
  if (lambda <= 0) return 0.0;
  double x = fit.model == FitModel::logistic ? lambda : std::log(lambda);
  return standard_cdf(fit.model, (x - fit.location) / fit.scale);
}

void bootstrap_threshold(Fit& fit, double step, int resamples, uint64_t seed) {
  const double start[2] = {fit.location, std::log(fit.scale)};
  // Each resample has its own random stream, so the result does not depend on scheduling.
  std::vector<double> results(size_t(resamples), std::nan(""));
  tbb::parallel_for(0, resamples, [&](int b) {
    std::vector<double> sample(fit.n);
    SampleStream random(seed, 5, uint64_t(b), 0);
    for (double& x : sample) {
      // Inverse-CDF draw, then the grid answer whose interval contains it.
      double u = std::clamp(random.next(), 1e-12, 1.0 - 1e-12), z;
      switch (fit.model) {
        case FitModel::lognormal: z = -std::numbers::sqrt2 * boost::math::erfc_inv(2.0 * u); break;
        case FitModel::weibull: z = std::log(-std::log(1.0 - u)); break;
        default: z = std::log(u / (1.0 - u));
      }
      double v = fit.location + fit.scale * z;
      double lambda = fit.model == FitModel::logistic ? v : std::exp(v);
      x = std::max(1.0, std::ceil(lambda / step - 1e-9)) * step;
    }
    Fit refit = solve(count_answers(sample, step), step, fit.model, start);
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
    return i + 1 < thresholds.size() ? thresholds[i] + frac * (thresholds[i + 1] - thresholds[i]) : thresholds[i];
  };
  fit.ci_low = quantile(0.025);
  fit.ci_high = quantile(0.975);
}

}  // namespace countershade::analysis
