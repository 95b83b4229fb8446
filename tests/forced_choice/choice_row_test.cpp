// Replaying a forced-choice session's rows (a resume, or a page reload): every answer position
// of an n-alternative task comes back, and a row that is not the planned trial is refused.

#include "forced_choice/choice_row.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "web_engine/page_study.h"

namespace countershade::forced_choice {
namespace {

using nlohmann::json;

// One condition on λ = 0, 0.1, …, 1.
runtime::Study one_condition() {
  json grid = json::array();
  for (int k = 0; k <= 10; ++k) grid.push_back(k * 0.1);
  return web_engine::study_from_page(
      {{"lambda_grid", {{"min", 0}, {"step", 0.1}}},
       {"conditions",
        {{{"scene", "cube"}, {"method", "usm3d"}, {"sigma_value", 0.02}, {"grid", grid}}}}});
}

ChoiceConfig four_afc() {
  return procedures::parse_choice_config(json::parse(R"({"n_afc": 4, "practice_trials": 2,
                      "procedure": {"type": "constant", "lambdas": [0.3, 0.6], "repetitions": 4}})"),
                                         "test", "");
}

TEST(ChoiceRows, EveryPositionOfAFourAlternativeTaskIsReplayed) {
  const runtime::Study study = one_condition();
  const ChoiceConfig config = four_afc();
  ChoiceRun first(study, config, 17);
  std::vector<std::vector<std::string>> rows;
  std::vector<int> responses;
  for (int k = 0; first.current(); ++k) {
    const ChoiceTrial t = *first.current();
    const int response = k % 4;  // every position, right or wrong
    first.answer(response);
    if (!t.practice)
      rows.push_back(choice_row(study, config, {"P", 1, "S"}, t, response, false, 0.4, "T"));
    if (!t.practice) responses.push_back(response);
  }
  ASSERT_EQ(rows.size(), 8u);
  ChoiceRun again(study, config, 17);
  replay_choice_rows(again, rows, study, config.n_afc, [](size_t r) { return std::to_string(r); });
  EXPECT_TRUE(again.finished());
  EXPECT_EQ(again.procedure_state(0), first.procedure_state(0));
  EXPECT_NE(std::find(responses.begin(), responses.end(), 3), responses.end());
}

TEST(ChoiceRows, ARowThatIsNotThePlannedTrialIsRefused) {
  const runtime::Study study = one_condition();
  const ChoiceConfig config = four_afc();
  ChoiceRun first(study, config, 17);
  while (first.in_practice()) first.answer(0);
  auto row = choice_row(study, config, {"P", 1, "S"}, *first.current(), 1, false, 0.4, "T");
  auto wrong_target = row;
  wrong_target[kColumnTarget] = std::to_string((std::stoi(row[kColumnTarget]) + 1) % 4);
  auto wrong_response = row;
  wrong_response[kColumnResponse] = "4";
  for (const auto& bad : {wrong_target, wrong_response}) {
    ChoiceRun again(study, config, 17);
    try {
      replay_choice_rows(again, {bad}, study, config.n_afc, [](size_t) { return "row 1"; });
      FAIL() << "accepted a row that is not the plan's";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("row 1"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace countershade::forced_choice
