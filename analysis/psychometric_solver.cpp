#include "analysis/psychometric_solver.h"

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/special_functions/erf.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <stdexcept>

#include "core/error.h"

namespace countershade::analysis {

CellData::CellData(std::vector<BinomialCell> c) : cells(std::move(c)) {
  for (const BinomialCell& cell : cells) {
    x.push_back(std::log(cell.lambda));
    const double k = double(cell.k), n = double(cell.n);
    saturated_nll -=
        (k > 0 ? k * std::log(k / n) : 0) + (n - k > 0 ? (n - k) * std::log((n - k) / n) : 0);
  }
}

BaseValue base_value(ThresholdModel model, double eta) {
  switch (model) {
    case ThresholdModel::weibull: {
      const double e = std::exp(eta), survive = std::exp(-e), f = e * survive;
      return {e < 1e-3 ? -std::expm1(-e) : 1 - survive, survive, f,
              f * (1 - e)};  // expm1 only where 1 − e^−e cancels
    }
    case ThresholdModel::log_logistic: {
      const double F = 1 / (1 + std::exp(-eta)), Fc = 1 / (1 + std::exp(eta)), f = F * Fc;
      return {F, Fc, f, f * (Fc - F)};
    }
    case ThresholdModel::log_normal: {
      const double f = std::exp(-0.5 * eta * eta) / std::sqrt(2 * M_PI);
      return {0.5 * std::erfc(-eta / std::sqrt(2.0)), 0.5 * std::erfc(eta / std::sqrt(2.0)), f,
              -eta * f};
    }
    case ThresholdModel::logistic:
      break;  // on λ itself: not a function of ln λ (kPsychometricModels)
  }
  throw std::logic_error(std::string("psychometric fit: no base function ") +
                         threshold_model_name(model));
}

// F⁻¹(p): the η where the base function reaches p.
double inverse_base(ThresholdModel model, double p) {
  switch (model) {
    case ThresholdModel::weibull:
      return std::log(-std::log1p(-p));
    case ThresholdModel::log_logistic:
      return std::log(p / (1 - p));
    case ThresholdModel::log_normal:
      return -std::sqrt(2.0) * boost::math::erfc_inv(2 * p);
    case ThresholdModel::logistic:
      break;
  }
  throw std::logic_error(std::string("psychometric fit: no base function ") +
                         threshold_model_name(model));
}

// Cells sorted by λ, equal λ merged, each checked.
std::vector<BinomialCell> merge_cells(std::vector<BinomialCell> cells) {
  std::map<double, BinomialCell> by_lambda;
  for (const BinomialCell& c : cells) {
    if (!(c.lambda > 0) || !std::isfinite(c.lambda))
      throw InputError("psychometric fit: λ must be above 0");
    if (c.n <= 0 || c.k < 0 || c.k > c.n)
      throw InputError("psychometric fit: a cell needs 0 ≤ k ≤ n and n > 0");
    BinomialCell& m = by_lambda[c.lambda];
    m.lambda = c.lambda;
    m.k += c.k;
    m.n += c.n;
  }
  std::vector<BinomialCell> out;
  for (const auto& [lambda, c] : by_lambda) out.push_back(c);
  return out;
}

namespace {

constexpr double kTiny = 1e-300;

// k·ln(k/(n·p)), 0 when k = 0.
double deviance_term(double k, double n, double p) {
  return k > 0 ? k * std::log(k / (n * std::max(p, kTiny))) : 0;
}

struct CellProbability {
  double psi, q, dpsi, d2psi;  // ψ, 1 − ψ, dψ/dη, d²ψ/dη²
};
CellProbability cell_probability(ThresholdModel model, double guess, double lapse, double eta) {
  const BaseValue b = base_value(model, eta);
  const double a = 1 - guess - lapse;
  return {guess + a * b.F, a * b.Fc + lapse, a * b.f, a * b.df};
}

// −ln L and its derivatives in (b0, b1) at one point, in one pass over the cells.
struct Evaluation {
  double nll = 0;
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();
  Eigen::Matrix2d observed = Eigen::Matrix2d::Zero(), expected = Eigen::Matrix2d::Zero();
};

Evaluation evaluate(const CellData& data, const PsychometricOptions& o, double b0, double b1,
                    double lapse) {
  Evaluation e;
  for (size_t i = 0; i < data.size(); ++i) {
    const CellProbability p = cell_probability(o.model, o.guess, lapse, b0 + b1 * data.x[i]);
    const double k = double(data.cells[i].k), n = double(data.cells[i].n);
    const double psi = std::max(p.psi, kTiny), q = std::max(p.q, kTiny);
    e.nll -= (k > 0 ? k * std::log(psi) : 0) + (n - k > 0 ? (n - k) * std::log(q) : 0);
    const double first = -k / psi + (n - k) / q, second = k / (psi * psi) + (n - k) / (q * q);
    const Eigen::Vector2d z(1.0, data.x[i]);
    e.gradient += first * p.dpsi * z;
    e.observed += (second * p.dpsi * p.dpsi + first * p.d2psi) * z * z.transpose();
    e.expected += n * p.dpsi * p.dpsi / (psi * q) * z * z.transpose();
  }
  if (!std::isfinite(e.nll)) e.nll = std::numeric_limits<double>::infinity();
  return e;
}

// Fisher scoring (R glm's iteration) while far from the optimum, Newton steps with the observed
// information near it, each step halved until the likelihood does not fall.
LapseSolution solve_coefficients(const CellData& data, const PsychometricOptions& o, double lapse,
                                 CoefficientStart start, double tolerance) {
  LapseSolution s{start.intercept, start.slope, lapse};
  Evaluation e = evaluate(data, o, s.intercept, s.slope, lapse);
  bool near = false;
  for (int iteration = 0; iteration < 300; ++iteration) {
    const bool newton = near && e.observed.determinant() > 0 && e.observed(0, 0) > 0;
    const Eigen::Matrix2d& m = newton ? e.observed : e.expected;
    if (!(m.determinant() > 0)) break;
    const Eigen::Vector2d step = -m.inverse() * e.gradient;
    double t = 1;
    Evaluation next;
    for (; t > 1e-12; t *= 0.5) {
      next = evaluate(data, o, s.intercept + t * step[0], s.slope + t * step[1], lapse);
      if (next.nll <= e.nll + 1e-13 * std::abs(e.nll)) break;
    }
    if (t <= 1e-12) {  // no step lowers the likelihood any more: at the optimum's rounding floor
      s.converged = near;
      break;
    }
    s.intercept += t * step[0];
    s.slope += t * step[1];
    e = next;
    const double size = std::abs(t * step[0]) + std::abs(t * step[1]);
    if (!std::isfinite(s.slope) || std::abs(s.slope) > 1e6) break;
    near = near || size < 1e-4 * (1 + std::abs(s.intercept) + std::abs(s.slope));
    if (size <= tolerance * (1 + std::abs(s.intercept) + std::abs(s.slope))) {
      s.converged = true;
      break;
    }
  }
  s.deviance = 2 * (e.nll - data.saturated_nll);
  return s;
}

// Minimises the profile deviance over ℓ in [lo, hi] by golden-section search.
double golden_section(const std::function<double(double)>& f, double lo, double hi) {
  const double r = (std::sqrt(5.0) - 1) / 2;
  double a = lo, b = hi, c = b - r * (b - a), d = a + r * (b - a), fc = f(c), fd = f(d);
  while (b - a > 1e-11) {
    if (fc < fd) {
      b = d, d = c, fd = fc, c = b - r * (b - a), fc = f(c);
    } else {
      a = c, c = d, fc = fd, d = a + r * (b - a), fd = f(d);
    }
  }
  return fc < fd ? c : d;
}

}  // namespace

LikelihoodTerms likelihood_terms(const CellData& data, const PsychometricOptions& o, double b0,
                                 double b1, double lapse) {
  LikelihoodTerms t;
  for (size_t i = 0; i < data.size(); ++i) {
    const CellProbability p = cell_probability(o.model, o.guess, lapse, b0 + b1 * data.x[i]);
    const double k = double(data.cells[i].k), n = double(data.cells[i].n);
    t.deviance += 2 * (deviance_term(k, n, p.psi) + deviance_term(n - k, n, p.q));
    t.loglik_bernoulli +=
        (k > 0 ? k * std::log(p.psi) : 0) + (n - k > 0 ? (n - k) * std::log(p.q) : 0);
    t.log_binomial_coefficients += std::lgamma(n + 1) - std::lgamma(k + 1) - std::lgamma(n - k + 1);
  }
  return t;
}

Eigen::MatrixXd expected_information(const CellData& data, const PsychometricOptions& o, double b0,
                                     double b1, double lapse, bool with_lapse) {
  const int size = with_lapse ? 3 : 2;
  Eigen::MatrixXd info = Eigen::MatrixXd::Zero(size, size);
  for (size_t i = 0; i < data.size(); ++i) {
    const double eta = b0 + b1 * data.x[i];
    const CellProbability p = cell_probability(o.model, o.guess, lapse, eta);
    Eigen::VectorXd z(size);  // dψ/d(b0, b1[, ℓ])
    z[0] = p.dpsi;
    z[1] = p.dpsi * data.x[i];
    if (with_lapse) z[2] = -base_value(o.model, eta).F;
    info += double(data.cells[i].n) / (p.psi * p.q) * z * z.transpose();
  }
  return info;
}

StepLimit step_limit(const CellData& data, const PsychometricOptions& o) {
  auto deviance_at = [&](size_t step, double lapse) {
    double d = 0;
    for (size_t i = 0; i < data.size(); ++i) {
      const double k = double(data.cells[i].k), n = double(data.cells[i].n);
      const double psi = i < step   ? o.guess
                         : i > step ? 1 - lapse
                                    : std::clamp(k / n, o.guess, 1 - lapse);
      const double q = 1 - psi;
      if ((k > 0 && psi <= 0) || (n - k > 0 && q <= 0))
        return std::numeric_limits<double>::infinity();
      d += 2 * (deviance_term(k, n, psi) + deviance_term(n - k, n, q));
    }
    return d;
  };
  StepLimit best{std::numeric_limits<double>::infinity(), data.cells.front().lambda};
  auto consider = [&](size_t step, double lapse) {
    const double d = deviance_at(step, std::clamp(lapse, 0.0, o.max_lapse));
    if (d < best.deviance) best = {d, data.cells[step].lambda};
  };
  for (size_t step = 0; step < data.size(); ++step) {
    if (!o.free_lapse) {
      consider(step, 0.0);
      continue;
    }
    // The likelihood in ℓ is concave on each piece; its maximiser is a piece's closed form or an
    // end.
    double wrong_above = 0, n_above = 0;
    for (size_t i = step + 1; i < data.size(); ++i) {
      wrong_above += double(data.cells[i].n - data.cells[i].k);
      n_above += double(data.cells[i].n);
    }
    const BinomialCell& at = data.cells[step];
    const double with_step = (wrong_above + double(at.n - at.k)) / (n_above + double(at.n));
    for (double lapse : {0.0, o.max_lapse, n_above > 0 ? wrong_above / n_above : 0.0, with_step,
                         1 - double(at.k) / double(at.n)})
      consider(step, lapse);
  }
  return best;
}

CoefficientStart starting_coefficients(const CellData& data, const PsychometricOptions& o) {
  double sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < data.size(); ++i) {
    const double n = double(data.cells[i].n), p = (double(data.cells[i].k) + 0.5) / (n + 1);
    const double F = std::clamp((p - o.guess) / (1 - o.guess), 0.05, 0.95);
    const double y = inverse_base(o.model, F);
    sw += n, sx += n * data.x[i], sy += n * y, sxx += n * data.x[i] * data.x[i],
        sxy += n * data.x[i] * y;
  }
  const double spread = sxx - sx * sx / sw;
  double slope = spread > 0 ? (sxy - sx * sy / sw) / spread : 1;
  if (!(slope > 0.1)) slope = 1;
  return {(sy - slope * sx) / sw, slope};
}

LapseSolution solve_fixed_lapse(const CellData& data, const PsychometricOptions& options,
                                CoefficientStart start, double lapse, double tolerance) {
  return solve_coefficients(data, options, lapse, start, tolerance);
}

// The deviance profiled over ℓ on a 0.0025 grid, each point started from its neighbour's
// coefficients; the best grid point refined by golden-section search, and the bounds kept exactly
// when the profile is lowest there.
LapseSolution solve_free_lapse(const CellData& data, const PsychometricOptions& options,
                               CoefficientStart start) {
  const int points = int(std::lround(options.max_lapse / 0.0025));
  std::vector<LapseSolution> profile;
  CoefficientStart warm = start;
  for (int i = 0; i <= points; ++i) {
    const double lapse = i == points ? options.max_lapse : i * 0.0025;
    profile.push_back(solve_fixed_lapse(data, options, warm, lapse));
    if (profile.back().converged) warm = {profile.back().intercept, profile.back().slope};
  }
  // Back down the grid from the other end: at one ℓ the coefficients can have two local optima,
  // and each pass can only follow the branch it started on.
  for (int i = points - 1; i >= 0; --i) {
    const LapseSolution other = solve_fixed_lapse(
        data, options, {profile[size_t(i) + 1].intercept, profile[size_t(i) + 1].slope},
        profile[size_t(i)].lapse);
    if (other.converged && other.deviance < profile[size_t(i)].deviance) profile[size_t(i)] = other;
  }
  int minima = 0;
  size_t best = 0;
  for (size_t i = 0; i < profile.size(); ++i) {
    const double d = profile[i].deviance;
    const bool left = i == 0 || d < profile[i - 1].deviance,
               right = i + 1 == profile.size() || d < profile[i + 1].deviance;
    minima += left && right;
    if (d < profile[best].deviance) best = i;
  }
  const CoefficientStart from{profile[best].intercept, profile[best].slope};
  auto deviance_at = [&](double lapse) {
    return solve_fixed_lapse(data, options, from, lapse).deviance;
  };
  const double lo = best == 0 ? 0.0 : profile[best - 1].lapse;
  const double hi = best + 1 == profile.size() ? options.max_lapse : profile[best + 1].lapse;
  LapseSolution refined =
      solve_fixed_lapse(data, options, from, golden_section(deviance_at, lo, hi));
  for (double bound : {0.0, options.max_lapse}) {
    const LapseSolution at_bound = solve_fixed_lapse(data, options, from, bound);
    if (at_bound.converged && at_bound.deviance <= refined.deviance) refined = at_bound;
  }
  refined.profile_minima = std::max(minima, 1);
  return refined;
}

}  // namespace countershade::analysis
