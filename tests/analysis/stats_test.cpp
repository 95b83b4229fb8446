#include "analysis/stats.h"

#include <gtest/gtest.h>

#include <cmath>

#include "analysis/cluster.h"

namespace countershade::analysis {
namespace {

TEST(Stats, HolmMatchesRsPAdjust) {
  // p.adjust(c(0.01, 0.04, 0.03, 0.005), "holm") = 0.03 0.06 0.06 0.02
  auto adjusted = holm({0.01, 0.04, 0.03, 0.005});
  EXPECT_NEAR(adjusted[0], 0.03, 1e-15);
  EXPECT_NEAR(adjusted[1], 0.06, 1e-15);
  EXPECT_NEAR(adjusted[2], 0.06, 1e-15);
  EXPECT_NEAR(adjusted[3], 0.02, 1e-15);
  EXPECT_EQ(holm({0.6, 0.9})[1], 1.0);
}

// R's p.adjust leaves an NA where it is and does not count it: p.adjust(c(0.01, NA, 0.04),
// "holm") = 0.02 NA 0.04. A NaN in the sort used to break its ordering.
TEST(Stats, HolmLeavesNaAndDoesNotCountIt) {
  const auto adjusted = holm({0.01, std::nan(""), 0.04});
  EXPECT_NEAR(adjusted[0], 0.02, 1e-15);
  EXPECT_TRUE(std::isnan(adjusted[1]));
  EXPECT_NEAR(adjusted[2], 0.04, 1e-15);
}

// The tails at the edges, as R's pf, pt and pchisq (Boost throws there, and `analyze` failed on
// answers without any variance between subjects): pf(Inf, 2, 4, lower = FALSE) = 0,
// pf(NaN, ...) = NaN, a df of 0 or NaN gives NaN.
TEST(Stats, TailsAtInfinityAndNaN) {
  EXPECT_EQ(f_upper(INFINITY, 2, 4), 0.0);
  EXPECT_TRUE(std::isnan(f_upper(NAN, 2, 4)));
  EXPECT_TRUE(std::isnan(f_upper(3.0, NAN, 4)));
  EXPECT_EQ(f_upper(0.0, 2, 4), 1.0);
  EXPECT_EQ(t_two_sided(-INFINITY, 3), 0.0);
  EXPECT_TRUE(std::isnan(t_two_sided(NAN, 3)));
  EXPECT_TRUE(std::isnan(t_two_sided(1.0, 0)));  // one subject: no df
  EXPECT_EQ(chi2_upper(INFINITY, 2), 0.0);
  EXPECT_TRUE(std::isnan(chi2_upper(NAN, 2)));
}

TEST(Stats, TTestKnownValues) {
  // {1, 2, 3, 4, 6} against 2: mean 3.2, variance 14.8/4 = 3.7, t = 1.2/√(3.7/5).
  TTest t = t_test({1, 2, 3, 4, 6}, 2.0);
  EXPECT_NEAR(t.t, 1.2 / std::sqrt(3.7 / 5.0), 1e-12);
  EXPECT_EQ(t.df, 4.0);
  // The 97.5% quantile of t with 4 df is 2.776445105 (tables): two-sided p = 0.05 there.
  EXPECT_NEAR(t_two_sided(2.776445105, 4.0), 0.05, 1e-9);
  EXPECT_NEAR(t_two_sided(-2.776445105, 4.0), 0.05, 1e-9);
}

TEST(Stats, OneWayRepeatedMeasuresMatchesHandComputation) {
  // 4 subjects × 3 conditions. SS_conditions = 4·Σ(m_j − m)², SS_error from residuals.
  Eigen::MatrixXd y(4, 3);
  y << 1, 2, 4, 2, 3, 3, 3, 5, 7, 1, 1, 2;
  auto rows = rm_anova(y, {{"c", 3}});
  ASSERT_EQ(rows.size(), 1u);
  // Condition means 1.75, 2.75, 4.0; grand 2.8333: SS_c = 4·(1.1736+0.0069+1.3611) = 10.1667.
  // Subject means 7/3, 8/3, 5, 4/3: SS_s = 3·Σ(ms − m)² = 65/3; SS_total = Σ(x − m)² = 107/3.
  const double ss_c = 61.0 / 6.0, ss_total = 107.0 / 3.0, ss_s = 65.0 / 3.0;
  const double ss_e = ss_total - ss_c - ss_s;
  EXPECT_NEAR(rows[0].F, (ss_c / 2) / (ss_e / 6), 1e-10);
  EXPECT_NEAR(rows[0].ges, ss_c / (ss_c + ss_e + ss_s), 1e-12);
  EXPECT_TRUE(rows[0].has_sphericity);
  EXPECT_LE(rows[0].gg_epsilon, 1.0);
  EXPECT_GE(rows[0].gg_epsilon, 0.5);  // the lower bound 1/(k−1)
}

TEST(Cluster, WardSeparatesTwoObviousGroupsAndLabelsByFirstAppearance) {
  Eigen::MatrixXd x(6, 2);
  x << 5, 5, 0, 0, 0.2, 0.1, 5.1, 4.9, 0.1, 0.3, 4.8, 5.2;
  Dendrogram d = ward_d2(x);
  EXPECT_EQ(d.merges.size(), 5u);
  for (size_t k = 1; k < d.heights.size(); ++k) EXPECT_GE(d.heights[k], d.heights[k - 1]);
  auto labels = cut_tree(d, 6, 2);
  EXPECT_EQ(labels, (std::vector<int>{1, 2, 2, 1, 2, 1}));
  EXPECT_EQ(d.order.size(), 6u);
}

// Distances that overflow (inf − inf in the update is NaN) still give a full tree: every step
// merges some pair. The first closest-pair search found none and indexed cluster −1.
TEST(Cluster, WardMergesEverythingEvenWhenDistancesAreNotNumbers) {
  Eigen::MatrixXd x(4, 1);
  x << 1e300, -1e300, 0, 1;
  const Dendrogram d = ward_d2(x);
  EXPECT_EQ(d.merges.size(), 3u);
  EXPECT_EQ(d.order.size(), 4u);
  EXPECT_EQ(cut_tree(d, 4, 2).size(), 4u);
}

}  // namespace
}  // namespace countershade::analysis
