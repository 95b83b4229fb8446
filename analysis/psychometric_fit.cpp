#include "analysis/psychometric_fit.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "analysis/psychometric_solver.h"
#include "core/error.h"

namespace countershade::analysis {

namespace {

// Standard errors of b0, b1 and of ln threshold from the inverse expected information.
void standard_errors(PsychometricFit& fit, const CellData& data) {
  const Eigen::MatrixXd info =
      expected_information(data, fit.options, fit.intercept, fit.slope, fit.lapse,
                           fit.options.free_lapse && !fit.lapse_at_bound);
  Eigen::FullPivLU<Eigen::MatrixXd> lu(info);
  if (!lu.isInvertible()) {
    fit.se_intercept = fit.se_slope = fit.threshold_se = std::numeric_limits<double>::infinity();
    return;
  }
  const Eigen::MatrixXd cov = lu.inverse();
  fit.se_intercept = std::sqrt(cov(0, 0));
  fit.se_slope = std::sqrt(cov(1, 1));
  const double centre = inverse_base(fit.options.model, 0.5);
  const Eigen::Vector2d gradient(-1 / fit.slope,
                                 -(centre - fit.intercept) / (fit.slope * fit.slope));
  fit.threshold_se = fit.threshold * std::sqrt(gradient.dot(cov.topLeftCorner<2, 2>() * gradient));
}

void summary_statistics(PsychometricFit& fit, const CellData& data) {
  const int parameters = fit.options.free_lapse ? 3 : 2;
  const LikelihoodTerms terms =
      likelihood_terms(data, fit.options, fit.intercept, fit.slope, fit.lapse);
  fit.deviance = terms.deviance;
  fit.loglik_bernoulli = terms.loglik_bernoulli;
  fit.loglik_binomial = terms.loglik_bernoulli + terms.log_binomial_coefficients;
  fit.aic = -2 * fit.loglik_binomial + 2 * parameters;
  fit.df = int(data.size()) - parameters;
  const double g = fit.options.guess;
  fit.threshold = std::exp((inverse_base(fit.options.model, 0.5) - fit.intercept) / fit.slope);
  const double f_at_psi = ((1 - g) / 2) / (1 - g - fit.lapse);
  fit.threshold_psi =
      std::exp((inverse_base(fit.options.model, f_at_psi) - fit.intercept) / fit.slope);
}

// Separated data: the slope runs off to infinity and the threshold to the step's position; the
// value where the iteration stopped would only say where rounding made the likelihood flat.
void compare_with_steepest(PsychometricFit& fit, const CellData& data) {
  const StepLimit steepest = step_limit(data, fit.options);
  fit.deviance_step_limit = steepest.deviance;
  if (!fit.converged && steepest.deviance <= fit.deviance + 1e-6) {
    fit.threshold = fit.threshold_psi = steepest.lambda;
    fit.threshold_se = std::numeric_limits<double>::infinity();
  }
}

}  // namespace

PsychometricFit fit_psychometric(std::vector<BinomialCell> cells,
                                 const PsychometricOptions& options) {
  PsychometricFit fit;
  fit.options = options;
  const CellData data(merge_cells(std::move(cells)));
  fit.n_cells = data.size();
  for (const BinomialCell& c : data.cells) fit.n_trials += c.n;
  if (data.size() < 2) throw InputError("psychometric fit: needs trials at two λ values at least");
  const CoefficientStart start = starting_coefficients(data, options);
  const LapseSolution best = options.free_lapse ? solve_free_lapse(data, options, start)
                                                : solve_fixed_lapse(data, options, start);
  fit.intercept = best.intercept;
  fit.slope = best.slope;
  fit.lapse = best.lapse;
  fit.profile_minima = best.profile_minima;
  fit.converged = best.converged;
  fit.lapse_at_bound = options.free_lapse && (best.lapse == 0 || best.lapse == options.max_lapse);
  summary_statistics(fit, data);
  standard_errors(fit, data);
  compare_with_steepest(fit, data);
  fit.well_defined = fit.converged && !(fit.deviance_step_limit < fit.deviance - 1e-9) &&
                     std::abs(fit.slope) < 50 && fit.profile_minima == 1 &&
                     (options.free_lapse || fit.se_slope < std::abs(fit.slope));
  return fit;
}

double psychometric_probability(const PsychometricFit& fit, double lambda) {
  const BaseValue b = base_value(fit.options.model, fit.intercept + fit.slope * std::log(lambda));
  return fit.options.guess + (1 - fit.options.guess - fit.lapse) * b.F;
}

}  // namespace countershade::analysis
