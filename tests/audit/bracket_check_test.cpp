// The audit's bracket check on predictions made by hand: a condition passes with its λ at 1 JND
// three grid steps up and its λ at 4 JND inside the grid, fails with fewer steps below, with the
// grid ending first or with no visible step at all; a control passes. The suggested grid has a
// quarter of the smallest threshold as its step and reaches a quarter above the largest 4 JND.

#include "audit/bracket_check.h"

#include <gtest/gtest.h>

namespace countershade {
namespace {

observer::ConditionPrediction condition(const std::string& scene, double jnd_per_lambda,
                                        const LambdaGridInfo& grid) {
  observer::ConditionPrediction c;
  c.scene = scene;
  c.method = "usm3d";
  c.sigma = 0.1;
  for (int i = 0; i < grid.count; ++i) {
    c.lambda.push_back(grid.min + i * grid.step);
    c.jnd.push_back(jnd_per_lambda * c.lambda.back());
  }
  for (size_t l = 0; l < 3; ++l) {
    const double at = observer::kPredictionLevels[l] / jnd_per_lambda;
    if (jnd_per_lambda > 0 && at <= grid.max) c.lambda_at[l] = at;
  }
  return c;
}

TEST(BracketCheck, NamesTheConditionsThatFallShortAndSuggestsAGrid) {
  const LambdaGridInfo grid{0, 1, 0.1, 11};
  observer::SetPrediction p;
  p.conditions = {condition("bracketed", 2.5, grid),   // 1 JND at 0.4: three steps below
                  condition("too-coarse", 5.0, grid),  // 1 JND at 0.2: one step below
                  condition("too-short", 2.0, grid),   // 4 JND at 2, beyond the grid
                  condition("invisible", 0.5, grid),   // 0.5 JND at the top
                  condition("control", 0.0, grid)};
  p.conditions[0].jnd.back() = 4.5;  // and made to reach 4 JND just below the top
  p.conditions[0].lambda_at[2] = 0.96;
  AuditReport report;
  add_bracket_checks(report, p, grid, 36);
  ASSERT_EQ(report.checks.size(), 5u);
  const bool expected[] = {true, false, false, false, true};
  for (size_t i = 0; i < 5; ++i)
    EXPECT_EQ(report.checks[i].passed, expected[i])
        << report.checks[i].scene << ": " << report.checks[i].detail;
  EXPECT_NE(report.checks[1].detail.find("1 grid step(s) below"), std::string::npos)
      << report.checks[1].detail;
  EXPECT_NE(report.checks[3].detail.find("never reaches 1 JND"), std::string::npos);
  ASSERT_EQ(report.notes.size(), 1u);
  EXPECT_NE(report.notes[0].find("3 condition(s) fall short"), std::string::npos)
      << report.notes[0];
  // Smallest λ at 1 JND: 0.2 (too-coarse) → step 0.05; largest λ at 4 JND: 8 (invisible,
  // extrapolated from 0.5 JND at λ 1) → max 10 (a quarter above, on the step).
  const auto g = bracketing_grid(p);
  ASSERT_TRUE(g);
  EXPECT_DOUBLE_EQ(g->step, 0.05);
  EXPECT_DOUBLE_EQ(g->max, 10);
  EXPECT_EQ(g->count(), 201);
  EXPECT_NE(report.notes[0].find("\"step\": 0.05"), std::string::npos) << report.notes[0];
}

}  // namespace
}  // namespace countershade
