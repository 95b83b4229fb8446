#pragma once
// Statistics with the conventions of R: repeated-measures ANOVA as afex/car report it (F, df,
// p, generalised η², Mauchly's test, Greenhouse–Geisser and Huynh–Feldt corrections), t-tests,
// Holm's correction. Distributions come from Boost.Math, linear algebra from Eigen.

#include <Eigen/Dense>
#include <string>
#include <vector>

namespace countershade::analysis {

struct Summary {
  size_t n = 0;
  double mean = 0, sd = 0, sem = 0;  // sd with n − 1
};
Summary summarize(const std::vector<double>& values);

struct TTest {
  double mean = 0, t = 0, df = 0, p = 0;  // two-sided p
};
// One-sample t-test of `values` against `mu`; for a paired test pass the differences and mu = 0.
TTest t_test(const std::vector<double>& values, double mu);

// Holm's step-down adjustment, as R's p.adjust(method = "holm"); keeps the input order.
std::vector<double> holm(const std::vector<double>& p);

struct WithinFactor {
  std::string name;
  int levels = 0;
};

struct AnovaRow {
  std::string effect;  // "question", "question:scene", ...
  double df1 = 0, df2 = 0, F = 0, p = 0, ges = 0;
  // Mauchly and the corrections exist only when df1 > 1 and there are more subjects than df1.
  bool has_sphericity = false;
  double mauchly_W = 0, mauchly_p = 0, gg_epsilon = 1, p_gg = 0, hf_epsilon = 1, p_hf = 0;
};

// Fully within-subject ANOVA. `data` is subjects × cells, the cells in row-major order of
// `factors` (the first factor varies slowest). Effects come in R's order: main effects, then
// two-way interactions, and so on, each in factor order.
std::vector<AnovaRow> rm_anova(const Eigen::MatrixXd& data,
                               const std::vector<WithinFactor>& factors);

// Upper-tail probabilities.
double f_upper(double F, double df1, double df2);
double t_two_sided(double t, double df);
double chi2_upper(double x, double df);

}  // namespace countershade::analysis
