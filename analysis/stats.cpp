#include "analysis/stats.h"

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>
#include <numeric>

namespace countershade::analysis {

Summary summarize(const std::vector<double>& v) {
  Summary s;
  s.n = v.size();
  if (v.empty()) return s;
  s.mean = std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
  double ss = 0;
  for (double x : v) ss += (x - s.mean) * (x - s.mean);
  s.sd = v.size() > 1 ? std::sqrt(ss / double(v.size() - 1)) : 0.0;
  s.sem = s.sd / std::sqrt(double(v.size()));
  return s;
}

// The upper tails follow R's pf, pt and pchisq at the edges, where Boost throws: a statistic or a
// df that is not a number gives NaN (NA), an infinite statistic 0. Data without any variance give
// such statistics (F = effect / 0 = inf, 0 / 0 = NaN).
namespace {
constexpr double kNotAvailable = std::numeric_limits<double>::quiet_NaN();
bool usable_df(double df) { return df > 0 && std::isfinite(df); }
}  // namespace

double f_upper(double F, double df1, double df2) {
  if (std::isnan(F) || !usable_df(df1) || !usable_df(df2)) return kNotAvailable;
  if (!(F > 0)) return 1.0;
  if (std::isinf(F)) return 0.0;
  return boost::math::cdf(boost::math::complement(boost::math::fisher_f(df1, df2), F));
}

double t_two_sided(double t, double df) {
  if (std::isnan(t) || !usable_df(df)) return kNotAvailable;
  if (std::isinf(t)) return 0.0;
  return 2.0 * boost::math::cdf(boost::math::complement(boost::math::students_t(df), std::abs(t)));
}

double chi2_upper(double x, double df) {
  if (std::isnan(x) || !usable_df(df)) return kNotAvailable;
  if (!(x > 0)) return 1.0;
  if (std::isinf(x)) return 0.0;
  return boost::math::cdf(boost::math::complement(boost::math::chi_squared(df), x));
}

TTest t_test(const std::vector<double>& values, double mu) {
  Summary s = summarize(values);
  TTest r;
  r.mean = s.mean;
  r.df = double(s.n) - 1.0;
  r.t = (s.mean - mu) / s.sem;
  r.p = t_two_sided(r.t, r.df);
  return r;
}

std::vector<double> holm(const std::vector<double>& p) {
  // As R: an NA stays NA and does not count among the m tests (NaN would also break the sort).
  std::vector<size_t> order;
  for (size_t i = 0; i < p.size(); ++i)
    if (!std::isnan(p[i])) order.push_back(i);
  const size_t m = order.size();
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return p[a] < p[b]; });
  std::vector<double> adjusted(p.size(), kNotAvailable);
  double running = 0;
  for (size_t k = 0; k < m; ++k) {
    running = std::max(running, std::min(1.0, double(m - k) * p[order[k]]));
    adjusted[order[k]] = running;
  }
  return adjusted;
}

namespace {

// Orthonormal contrasts (levels−1 rows, each orthogonal to the constant), from Helmert contrasts.
Eigen::MatrixXd contrasts(int levels) {
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(levels - 1, levels);
  for (int k = 1; k < levels; ++k) {
    for (int j = 0; j < k; ++j) c(k - 1, j) = -1.0;
    c(k - 1, k) = double(k);
    c.row(k - 1).normalize();
  }
  return c;
}

Eigen::MatrixXd kron(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  Eigen::MatrixXd out(a.rows() * b.rows(), a.cols() * b.cols());
  for (int i = 0; i < a.rows(); ++i)
    for (int j = 0; j < a.cols(); ++j)
      out.block(i * b.rows(), j * b.cols(), b.rows(), b.cols()) = a(i, j) * b;
  return out;
}

// The transform for one effect: contrasts for its factors, normalised averaging for the others.
Eigen::MatrixXd effect_transform(const std::vector<WithinFactor>& factors,
                                 const std::vector<bool>& in_effect) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Ones(1, 1);
  for (size_t f = 0; f < factors.size(); ++f) {
    Eigen::MatrixXd part =
        in_effect[f]
            ? contrasts(factors[f].levels)
            : Eigen::MatrixXd::Constant(1, factors[f].levels, 1.0 / std::sqrt(factors[f].levels));
    m = kron(m, part);
  }
  return m;
}

struct EffectSS {
  double ss_effect = 0, ss_error = 0;
  Eigen::MatrixXd covariance;  // of the transformed scores, p × p
};

EffectSS sums_of_squares(const Eigen::MatrixXd& data, const Eigen::MatrixXd& transform) {
  Eigen::MatrixXd y = data * transform.transpose();  // subjects × p
  Eigen::RowVectorXd mean = y.colwise().mean();
  Eigen::MatrixXd centred = y.rowwise() - mean;
  EffectSS s;
  s.ss_effect = double(y.rows()) * mean.squaredNorm();
  s.ss_error = centred.squaredNorm();
  s.covariance = centred.transpose() * centred / double(y.rows() - 1);
  return s;
}

// Effects in R's order: by interaction order, then lexicographically by factor index.
std::vector<std::vector<bool>> effects_in_r_order(size_t nf) {
  std::vector<std::vector<bool>> effects;
  for (size_t order = 1; order <= nf; ++order) {
    std::vector<bool> select(nf, false);
    std::fill(select.begin(), select.begin() + long(order), true);
    do effects.push_back(select);
    while (std::prev_permutation(select.begin(), select.end()));
  }
  return effects;
}

// Mauchly's test, Greenhouse–Geisser and Huynh–Feldt for an effect with p > 1 contrasts, from the
// covariance S of its transformed scores (n subjects, `cells` within-subject cells).
void add_sphericity(AnovaRow& row, const Eigen::MatrixXd& S, double n, double cells) {
  const double p = double(S.rows());
  row.has_sphericity = true;
  // Mauchly's test as afex reports it (car's Anova.mlm): its second-order correction term uses
  // the number of within-subject cells where R's mauchly.test uses p; kept for agreement.
  const double df = n - 1, trace = S.trace();
  const double log_w = std::log(S.determinant()) - p * std::log(trace / p);
  const double rho = 1.0 - (2 * p * p + p + 2) / (6 * p * df);
  const double w2 = (p + 2) * (p - 1) * (p - 2) * (2 * p * p * p + 6 * p * p + 3 * cells + 2) /
                    (288.0 * std::pow(df * p * rho, 2));
  const double z = -df * rho * log_w, f = p * (p + 1) / 2 - 1;
  const double pr1 = chi2_upper(z, f), pr2 = chi2_upper(z, f + 4);
  row.mauchly_W = std::exp(log_w);
  row.mauchly_p = pr1 + w2 * (pr2 - pr1);
  // Greenhouse–Geisser and Huynh–Feldt (car's formula, capped at 1).
  row.gg_epsilon = trace * trace / (p * (S * S).trace());
  const double hf = (n * p * row.gg_epsilon - 2) / (p * (n - 1 - p * row.gg_epsilon));
  row.hf_epsilon = std::isnan(hf) ? hf : std::min(1.0, hf);
  row.p_gg = f_upper(row.F, row.df1 * row.gg_epsilon, row.df2 * row.gg_epsilon);
  row.p_hf = f_upper(row.F, row.df1 * row.hf_epsilon, row.df2 * row.hf_epsilon);
}

}  // namespace

std::vector<AnovaRow> rm_anova(const Eigen::MatrixXd& data,
                               const std::vector<WithinFactor>& factors) {
  const size_t nf = factors.size();
  const double n = double(data.rows());
  const std::vector<std::vector<bool>> effects = effects_in_r_order(nf);
  // Between-subject variation (the intercept's error term) enters generalised η².
  const EffectSS subjects =
      sums_of_squares(data, effect_transform(factors, std::vector<bool>(nf, false)));
  std::vector<EffectSS> ss;
  double total_error = subjects.ss_error;
  for (const auto& e : effects) {
    ss.push_back(sums_of_squares(data, effect_transform(factors, e)));
    total_error += ss.back().ss_error;
  }
  std::vector<AnovaRow> rows;
  for (size_t k = 0; k < effects.size(); ++k) {
    AnovaRow row;
    for (size_t f = 0; f < nf; ++f)
      if (effects[k][f]) row.effect += (row.effect.empty() ? "" : ":") + factors[f].name;
    const double p = double(ss[k].covariance.rows());
    row.df1 = p;
    row.df2 = p * (n - 1);
    row.F = (ss[k].ss_effect / row.df1) / (ss[k].ss_error / row.df2);
    row.p = f_upper(row.F, row.df1, row.df2);
    row.ges = ss[k].ss_effect / (ss[k].ss_effect + total_error);
    // With fewer than p + 1 subjects the scores' covariance is singular: R (car, afex) reports no
    // sphericity test and no corrections then, and neither does this.
    if (p > 1 && n - 1 >= p) add_sphericity(row, ss[k].covariance, n, double(data.cols()));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace countershade::analysis
