// Adjustment against forced choice: per condition, each subject's mean λ_Low beside their own
// forced-choice threshold, and a paired t-test on the log ratio computed here by hand.

#include "analysis/method_comparison.h"

#include <gtest/gtest.h>

#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <map>

#include "analysis/forced_choice_simulation.h"
#include "analysis/simulate.h"

namespace countershade::analysis {
namespace {

TEST(MethodComparison, PairsEachSubjectsLambdaLowWithTheirThreshold) {
  SimulationDesign adjustment;
  adjustment.subjects = 8;
  adjustment.scenes = {"dice"};
  adjustment.sigmas = {0.02};
  adjustment.method = "usm3d";
  AnalysisOptions options;
  const std::vector<Response> responses = simulate_responses(adjustment);
  const std::vector<BlockResults> blocks = analyze(responses, options);

  ForcedChoiceDesign fc;
  fc.subjects = 8;
  fc.method = "usm3d";
  fc.subject_sd = 0.2;
  fc.conditions = {{"dice", 0.02, 0.35, 3.0, {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8}}};
  ForcedChoiceOptions fc_options;
  fc_options.bootstrap = 0;
  const ForcedChoiceResults fits = analyze_forced_choice(simulate_forced_choice(fc), fc_options);

  const auto rows = compare_methods(blocks, fits);
  ASSERT_EQ(rows.size(), 1u);
  const MethodComparison& c = rows[0];
  EXPECT_EQ(c.scene, "dice");
  EXPECT_EQ(c.method, "usm3d");
  ASSERT_EQ(c.subjects.size(), 8u);
  std::map<std::string, double> low;  // the raw answers, averaged here
  std::map<std::string, int> count;
  for (const Response& r : responses)
    if (r.question == Question::low) low[r.subject] += r.lambda, ++count[r.subject];
  std::vector<double> differences;
  for (size_t i = 0; i < c.subjects.size(); ++i) {
    EXPECT_NEAR(c.lambda_low[i], low[c.subjects[i]] / count[c.subjects[i]], 1e-12) << c.subjects[i];
    for (const PsychometricRow& row : fits.rows) {
      if (row.pooled || row.subject != c.subjects[i]) continue;
      EXPECT_EQ(c.threshold[i], row.fit.threshold);
    }
    differences.push_back(std::log(c.lambda_low[i] / c.threshold[i]));
  }
  double mean = 0, ss = 0;
  for (double d : differences) mean += d / 8;
  for (double d : differences) ss += (d - mean) * (d - mean);
  const double t = mean / std::sqrt(ss / 7 / 8);
  EXPECT_NEAR(c.t, t, 1e-9 * std::abs(t));
  EXPECT_EQ(c.df, 7);
  EXPECT_NEAR(
      c.p, 2 * boost::math::cdf(boost::math::complement(boost::math::students_t(7), std::abs(t))),
      1e-12);
}

}  // namespace
}  // namespace countershade::analysis
