// Preparation rules: method blocks, exclusions, JND normalisation.

#include <gtest/gtest.h>

#include "analysis/analysis.h"
#include "analysis/simulate.h"

namespace countershade::analysis {
namespace {

std::vector<Response> small_study(int subjects, uint64_t seed) {
  SimulationDesign d;
  d.subjects = subjects;
  d.scenes = {"a", "b"};
  d.sigmas = {0.01, 0.02};
  d.seed = seed;
  return simulate_responses(d);
}

TEST(Preparation, EachMethodIsItsOwnBlock) {
  auto rows = small_study(6, 1);
  auto other = small_study(5, 2);
  for (auto& r : other) r.method = "usm2d";
  rows.insert(rows.end(), other.begin(), other.end());
  auto blocks = analyze(rows, AnalysisOptions{});
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_EQ(blocks[0].method, "simulated");
  EXPECT_EQ(blocks[0].json["n_subjects"], 6);
  EXPECT_EQ(blocks[1].method, "usm2d");
  EXPECT_EQ(blocks[1].json["n_subjects"], 5);
}

TEST(Preparation, ALowOfZeroExcludesTheSubjectWithAReason) {
  auto rows = small_study(6, 3);
  for (auto& r : rows)
    if (r.subject == "S002" && r.question == Question::low && r.scene == "b") r.lambda = 0.0;
  auto blocks = analyze(rows, AnalysisOptions{});
  ASSERT_EQ(blocks[0].excluded.size(), 1u);
  EXPECT_EQ(blocks[0].excluded[0].subject, "S002");
  EXPECT_NE(blocks[0].excluded[0].reason.find("lambda_low of 0"), std::string::npos);
  EXPECT_EQ(blocks[0].json["n_subjects"], 5);
}

// Under group normalisation nothing is divided by a subject's own λ_Low, so a λ_Low of 0 keeps
// the subject; the λ = 0 answers count as (0, λ_1] in the fits, with a warning per cell.
TEST(Preparation, ALowOfZeroExcludesOnlyUnderSubjectNormalisation) {
  auto rows = small_study(6, 3);
  for (auto& r : rows)
    if (r.subject == "S002" && r.question == Question::low && r.scene == "b") {
      r.lambda = 0.0;
      r.lambda_index = 0;
    }
  AnalysisOptions group;
  group.normalization = analysis::JndNormalization::group;
  auto blocks = analyze(rows, group);
  EXPECT_TRUE(blocks[0].excluded.empty());
  EXPECT_EQ(blocks[0].json["n_subjects"], 6);
  int zero_warnings = 0;
  for (const auto& w : blocks[0].warnings)
    zero_warnings += w.find("answers of lambda = 0") != std::string::npos;
  EXPECT_EQ(zero_warnings, 2);  // scene b at both σ
}

TEST(Preparation, GroupNormalisationDividesByTheMeanLow) {
  auto rows = small_study(8, 4);
  AnalysisOptions group;
  group.normalization = analysis::JndNormalization::group;
  auto blocks = analyze(rows, group);
  // Under group normalisation the mean λ_Low of every scene × σ is exactly 1 JND, while single
  // subjects vary around it (under subject normalisation every λ_Low is 1).
  for (const auto& d : blocks[0].json["descriptives_by_sigma"])
    if (d["question"] == "low") {
      EXPECT_NEAR(d["mean"].get<double>(), 1.0, 1e-12);
      EXPECT_GT(d["sd"].get<double>(), 0.0);
    }
  auto subject = analyze(rows, AnalysisOptions{});
  for (const auto& d : subject[0].json["descriptives_by_sigma"])
    if (d["question"] == "low") {
      EXPECT_EQ(d["sd"].get<double>(), 0.0);
    }
}

TEST(Preparation, RepeatedAnswersAreAveragedWithAWarning) {
  auto rows = small_study(5, 5);
  auto again = rows;
  for (auto& r : again) r.lambda += 0.1;  // a second repetition, 0.1 higher everywhere
  rows.insert(rows.end(), again.begin(), again.end());
  auto blocks = analyze(rows, AnalysisOptions{});
  bool warned = false;
  for (const auto& w : blocks[0].warnings) warned |= w.find("averaged") != std::string::npos;
  EXPECT_TRUE(warned);
  EXPECT_EQ(blocks[0].json["fits"][0]["n"], 10);  // fits keep repetitions as separate answers
}

}  // namespace
}  // namespace countershade::analysis
