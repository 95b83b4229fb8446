// Model observers (--observer model:SEED): the spec, the forced-choice Weibull in JND (84 %
// correct at 1 JND in 2AFC), the interpolated response, and the adjustment observer's thresholds
// at the prediction's 1, 2 and 4 JND with the same individual factors as the simulated observer;
// the prediction equals what `countershade predict` writes for the same set.

#include "observer/model_observer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "adjust/simulated_observer.h"
#include "adjust/tiny_set.h"
#include "formats/responses.h"
#include "runtime/study.h"
#include "test_util.h"

namespace countershade::observer {
namespace {

TEST(ModelObserver, SpecIsModelSeedAndAnOptionalPixelsPerDegree) {
  EXPECT_FALSE(parse_model_observer("simulated:3"));
  const auto plain = parse_model_observer("model:7");
  ASSERT_TRUE(plain);
  EXPECT_EQ(plain->seed, 7u);
  EXPECT_FALSE(plain->ppd);
  const auto with_ppd = parse_model_observer("model:2:36.5");
  ASSERT_TRUE(with_ppd && with_ppd->ppd);
  EXPECT_DOUBLE_EQ(*with_ppd->ppd, 36.5);
  for (const char* bad :
       {"model:", "model:x", "model:1:", "model:1:0.5", "model:1:36x", "model:-1"})
    EXPECT_NE(testing::input_error_of([&] { parse_model_observer(bad); }).find("--observer"),
              std::string::npos)
        << bad;
}

TEST(ModelObserver, OneJndIsEightyFourPercentCorrectInTwoAlternatives) {
  EXPECT_NEAR(model_probability_correct(1, 2), 0.84, 1e-12);
  EXPECT_DOUBLE_EQ(model_probability_correct(0, 2), 0.5);
  EXPECT_DOUBLE_EQ(model_probability_correct(0, 4), 0.25);
  EXPECT_GT(model_probability_correct(1, 4), 0.75);
  EXPECT_NEAR(model_probability_correct(10, 3), 1.0, 1e-12);
  EXPECT_LT(model_probability_correct(0.9, 2), model_probability_correct(1.1, 2));
  const PredictedCondition c{{0, 0.5, 1}, {0, 2, 6}, {}};
  EXPECT_DOUBLE_EQ(c.jnd_at(0.25), 1);
  EXPECT_DOUBLE_EQ(c.jnd_at(0.75), 4);
  EXPECT_DOUBLE_EQ(c.jnd_at(2), 6);
}

// The model observer draws the same individual factors as the simulated observer (sensitivity,
// spread of best and high, answer noise); only the base of each question differs: the
// prediction's λ at 1, 2 and 4 JND instead of shares of the grid's top.
TEST(ModelObserver, AdjustmentThresholdsLieAtThePredictedLevelsTimesTheObserversFactors) {
  testing::TempDir dir;
  const runtime::Study study = runtime::load_study(testing::make_tiny_set(dir), std::nullopt);
  const double inf = std::numeric_limits<double>::infinity();
  adjust::SimulatedObserver::PredictedLevels levels(study.conditions.size(), {0.1, 0.25, 0.6});
  levels[1] = {0.2, inf, inf};
  adjust::SimulatedObserver model(4, study, 0.02, levels), simulated(4, study);
  for (int c = 0; c < int(study.conditions.size()); ++c) {
    const double top = study.lambda(study.conditions[size_t(c)].grid_size - 1);
    const double base[kQuestionCount] = {0.2 * top, 0.6 * top, 0.32 * top};  // low, high, best
    const double level[kQuestionCount] = {levels[size_t(c)][0], levels[size_t(c)][2],
                                          levels[size_t(c)][1]};
    for (int r = 1; r <= 2; ++r)
      for (Question q : {Question::low, Question::high, Question::best}) {
        const double factor = simulated.latent_lambda(c, r, q) / base[int(q)];
        if (std::isinf(level[int(q)])) {
          EXPECT_EQ(model.answer_index(c, r, q), study.conditions[size_t(c)].grid_size - 1);
          continue;
        }
        EXPECT_NEAR(model.latent_lambda(c, r, q), level[int(q)] * factor, 1e-12);
      }
  }
}

TEST(ModelObserver, ThePredictionIsWhatPredictWrites) {
  testing::TempDir dir;
  const auto manifest = testing::make_tiny_set(dir);
  const runtime::Study study = runtime::load_study(manifest, std::nullopt);
  std::vector<ConditionName> names;
  for (const auto& c : study.conditions) names.push_back({c.scene, c.method, c.sigma});
  EXPECT_NE(testing::input_error_of([&] {
              predict_conditions(manifest, names, {1, {}}, {});
            }).find("model:SEED:PPD"),
            std::string::npos);
  const auto predicted = predict_conditions(manifest, names, {1, 40.0}, {});
  ASSERT_EQ(predicted.size(), names.size());
  const auto run = testing::run_cli("predict " + manifest.string() + " -o " + (dir / "p").string() +
                                    " --ppd 40");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const CsvTable table = parse_csv(testing::read_file(dir / "p/predicted_thresholds.csv"), "csv");
  ASSERT_EQ(table.rows.size(), names.size() + 1);
  size_t compared = 0;
  for (size_t r = 1; r < table.rows.size(); ++r)
    for (size_t c = 0; c < names.size(); ++c) {
      if (table.rows[r][0] != names[c].scene || std::stod(table.rows[r][2]) != names[c].sigma)
        continue;
      ++compared;
      for (size_t l = 0; l < 3; ++l) {
        const std::string& text = table.rows[r][3 + l];
        if (text.empty())
          EXPECT_TRUE(std::isinf(predicted[c].lambda_at[l]));
        else
          EXPECT_NEAR(predicted[c].lambda_at[l], std::stod(text), 5e-4 * std::stod(text));
      }
    }
  EXPECT_EQ(compared, names.size());
}

}  // namespace
}  // namespace countershade::observer
