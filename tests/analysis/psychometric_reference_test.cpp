// Psychometric fits against R psyphy (tests/reference/psychometric): the binomial cells of every
// 2AFC and 4AFC data set, pooled and per subject, and the fits of the Weibull, logistic and probit
// models with the lapse fixed at 0 and free in [0, 0.1], to the tolerances of the reference's
// README.

#include <gtest/gtest.h>

#include <sstream>

#include "analysis/forced_choice_trials.h"
#include "analysis/psychometric_fit.h"
#include "core/json_reader.h"
#include "test_util.h"

namespace countershade::analysis {
namespace {

using json = nlohmann::json;

struct ModelCase {
  const char* reference;
  ThresholdModel model;
  bool free_lapse;
};
constexpr ModelCase kCases[] = {
    {"mafc.cloglog", ThresholdModel::weibull, false},
    {"mafc.logit", ThresholdModel::log_logistic, false},
    {"mafc.probit", ThresholdModel::log_normal, false},
    {"weibull_lapse", ThresholdModel::weibull, true},
    {"probit_lapse", ThresholdModel::log_normal, true},
};

// "S02|keys|0.01" or "keys|0.01" → its cells.
const std::vector<BinomialCell>& cells_of(const std::map<ConditionKey, ConditionCells>& conditions,
                                          const std::string& key) {
  std::vector<std::string> parts;
  std::stringstream s(key);
  for (std::string part; std::getline(s, part, '|');) parts.push_back(part);
  const bool pooled = parts.size() == 2;
  const ConditionKey condition{parts[pooled ? 0 : 1], "", std::stod(parts[pooled ? 1 : 2])};
  const ConditionCells& c = conditions.at(condition);
  return pooled ? c.pooled : c.by_subject.at(parts[0]);
}

void near_relative(double got, const json& expected, double tolerance, const std::string& what) {
  const double e = expected.get<double>();
  EXPECT_LE(std::abs(got - e), tolerance * std::abs(e)) << what << ": " << got << " against " << e;
}

void check_fixed_lapse(const PsychometricFit& fit, const json& e, const std::string& what) {
  EXPECT_EQ(fit.well_defined, e["well_defined"].get<bool>()) << what;
  EXPECT_EQ(fit.df, e["df_residual"].get<int>()) << what;
  EXPECT_EQ(fit.n_trials, e["n_trials"].get<long long>()) << what;
  if (e["deviance_step_limit"].is_number())
    near_relative(fit.deviance_step_limit, e["deviance_step_limit"], 1e-9, what + " step limit");
  else
    EXPECT_TRUE(std::isinf(fit.deviance_step_limit)) << what;
  if (!e["well_defined"]
           .get<bool>()) {  // separation: only the infimum of the deviance and the threshold
    EXPECT_FALSE(fit.converged) << what;
    EXPECT_NEAR(fit.deviance, e["deviance"].get<double>(), 1e-4) << what;
    // The threshold runs to the step's level as the slope grows: λ·exp(−η_step/b1). The reference's
    // is where R stopped (b1 = 392: 0.2·exp(−0.847/392) = 0.19957); countershade reports the limit,
    // the level of the step, which is the reference's threshold rounded to its λ grid (0.05).
    near_relative(fit.threshold, json(std::round(e["threshold"].get<double>() / 0.05) * 0.05),
                  1e-12, what + " threshold");
    near_relative(fit.threshold, e["threshold"], 2.5e-3, what + " threshold");
    return;
  }
  near_relative(fit.intercept, e["intercept"], 1e-6, what + " intercept");
  near_relative(fit.slope, e["slope"], 1e-6, what + " slope");
  near_relative(fit.se_intercept, e["se_intercept"], 1e-6, what + " se intercept");
  near_relative(fit.se_slope, e["se_slope"], 1e-6, what + " se slope");
  near_relative(fit.threshold, e["threshold"], 1e-6, what + " threshold");
  near_relative(fit.deviance, e["deviance"], 1e-6, what + " deviance");
  near_relative(fit.loglik_binomial, e["loglik_binomial"], 1e-6, what + " loglik");
  near_relative(fit.loglik_bernoulli, e["loglik_bernoulli"], 1e-6, what + " bernoulli loglik");
  near_relative(fit.aic, e["aic"], 1e-6, what + " aic");
}

void check_free_lapse(const PsychometricFit& fit, const json& e, const std::string& what) {
  EXPECT_EQ(fit.df, e["df_residual"].get<int>()) << what;
  near_relative(fit.deviance_step_limit, e["deviance_step_limit"], 1e-9, what + " step limit");
  if (!e["well_defined"].get<bool>()) {  // a finite local optimum, or a step-like solution
    const bool local =
        std::abs(fit.deviance - e["deviance"].get<double>()) <= 1e-6 * e["deviance"].get<double>();
    EXPECT_TRUE(local || fit.deviance >= fit.deviance_step_limit - 1e-6)
        << what << ": deviance " << fit.deviance;
    return;
  }
  EXPECT_TRUE(fit.well_defined) << what;
  near_relative(fit.deviance, e["deviance"], 1e-6, what + " deviance");
  EXPECT_EQ(fit.lapse_at_bound, e["lapse_at_bound"].get<bool>()) << what << ": lapse " << fit.lapse;
  EXPECT_NEAR(fit.lapse, e["lapse"].get<double>(), e["lapse_at_bound"].get<bool>() ? 1e-9 : 1e-4)
      << what;
  near_relative(fit.intercept, e["intercept"], 1e-4, what + " intercept");
  near_relative(fit.slope, e["slope"], 1e-4, what + " slope");
  near_relative(fit.threshold, e["threshold_F50"], 1e-4, what + " threshold");
  near_relative(fit.threshold_psi, e["threshold_psi"], 1e-4, what + " threshold ψ");
  near_relative(fit.aic, e["aic"], 1e-6, what + " aic");
}

void check_data_set(const std::string& name) {
  const json expected =
      parse_json_file(testing::reference_path("psychometric/" + name + ".expected.json"));
  const auto trials =
      read_forced_choice_trials({testing::reference_path("psychometric/" + name + ".csv")});
  const auto conditions = aggregate_cells(trials);
  for (const char* scope : {"pooled", "per_subject"})
    for (const auto& [key, e] : expected["cells"][scope].items()) {
      const auto& cells = cells_of(conditions, key);
      ASSERT_EQ(cells.size(), e["lambda"].size()) << key;
      for (size_t i = 0; i < cells.size(); ++i) {
        EXPECT_NEAR(cells[i].lambda, e["lambda"][i].get<double>(), 1e-12) << key;
        EXPECT_EQ(cells[i].k, e["k"][i].get<long long>()) << key;
        EXPECT_EQ(cells[i].n, e["n"][i].get<long long>()) << key;
      }
    }
  int compared = 0;
  for (const ModelCase& c : kCases)
    for (const char* scope : {"pooled", "per_subject"})
      for (const auto& [key, e] : expected["fits"][c.reference][scope].items()) {
        const PsychometricOptions options{c.model, expected["guess_rate"].get<double>(),
                                          c.free_lapse};
        const PsychometricFit fit = fit_psychometric(cells_of(conditions, key), options);
        const std::string what = name + " " + c.reference + " " + key;
        c.free_lapse ? check_free_lapse(fit, e, what) : check_fixed_lapse(fit, e, what);
        ++compared;
      }
  EXPECT_EQ(compared,
            5 * int(expected["cells"]["pooled"].size() + expected["cells"]["per_subject"].size()))
      << name;
}

TEST(PsychometricFit, EqualsPsyphyOnTheTwoAlternativeData) { check_data_set("afc2_a"); }
TEST(PsychometricFit, EqualsPsyphyOnTheFourAlternativeData) { check_data_set("afc4_a"); }

}  // namespace
}  // namespace countershade::analysis
