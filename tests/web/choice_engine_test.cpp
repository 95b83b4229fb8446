// The forced-choice engine the exported page runs (the app's C++ compiled to WebAssembly) against
// the app's native build: for the same study, block, subject and simulated observer (a Weibull in
// λ, or a model observer answering from the page's prediction), every trial
// (condition, λ, target, answer, correctness), every row of the trials CSV and every procedure's
// final state are the same, for constant stimuli, a staircase, QUEST and QUEST+; and a session
// rebuilt from its rows half-way (a reload) ends in the same states.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "forced_choice/choice_observer.h"
#include "forced_choice/choice_row.h"
#include "forced_choice/choice_run.h"
#include "test_util.h"
#include "web_engine/page_model.h"
#include "web_engine/page_study.h"

namespace countershade::web_engine {
namespace {

using forced_choice::ChoiceRun;
using nlohmann::json;

// Three conditions on the grid λ = 0, 0.05, …, 1.5; the third never changes with λ (a control,
// which practice leaves out).
json page_study(const json& forced_choice) {
  json conditions = json::array();
  for (int c = 0; c < 3; ++c) {
    json hashes = json::array({"reference-" + std::to_string(c)});
    for (int k = 0; k < 31; ++k)
      hashes.push_back(c == 2 || k == 0 ? "reference-" + std::to_string(c)
                                        : "image-" + std::to_string(c) + "-" + std::to_string(k));
    conditions.push_back({{"scene", c == 1 ? "bunny" : "cube"},
                          {"method", "usm3d"},
                          {"sigma_value", c == 1 ? 0.05 : 0.02 * (c + 1)},
                          {"grid", json::array()},
                          {"sha256", hashes}});
    for (int k = 0; k < 31; ++k) conditions.back()["grid"].push_back(k * 0.05);
  }
  return {{"seed", "18446744073709551557"},  // beyond 2^53
          {"lambda_grid", {{"min", 0}, {"step", 0.05}}},
          {"conditions", conditions},
          {"set", {{"sha256", "SET"}}},
          {"forced_choice", forced_choice}};
}

// A made-up prediction for the page's model observer: the response grows linearly with λ, at a
// rate per condition (the control, condition 2, never responds).
json page_model() {
  json model = json::array();
  for (int c = 0; c < 3; ++c) {
    json lambda = json::array(), jnd = json::array();
    for (int k = 0; k < 31; ++k) {
      lambda.push_back(k * 0.05);
      jnd.push_back(c == 2 ? 0.0 : (c + 1) * 3.0 * k * 0.05);
    }
    model.push_back({{"lambda_at", {nullptr, nullptr, nullptr}}, {"lambda", lambda}, {"jnd", jnd}});
  }
  return model;
}

// The app's session, answered by the simulated observer: each trial and the final states.
json native_session(const json& page, const std::string& subject, int session,
                    const std::string& observer_spec) {
  const runtime::Study study = study_from_page(page);
  const auto config =
      procedures::parse_choice_config(page["forced_choice"], "study.js", "forced_choice");
  const uint64_t seed = config.seed ? runtime::session_seed(*config.seed, subject, session)
                                    : page_session_seed(page, subject, session);
  ChoiceRun run(study, config, seed);
  const auto observer = page_choice_observer(page, observer_spec);
  json trials = json::array(), rows = json::array();
  for (int practice_index = 0; run.current();) {
    const auto t = *run.current();
    const int response =
        observer.respond(t.number, practice_index, t.lambda, t.target, config.n_afc, t.condition);
    const bool correct = run.answer(response);
    practice_index += t.practice;
    trials.push_back({t.number, t.practice, t.condition, t.condition_trial, t.intensity.requested,
                      t.lambda_index, t.lambda, t.target, response, correct});
    // The row with a response time the checker can repeat: 0.5 s plus 1 ms per trial.
    if (!t.practice)
      rows.push_back(forced_choice::choice_row(study, config, {subject, session, "SET"}, t,
                                               response, correct, 0.5 + 0.001 * t.number, "T"));
  }
  json states = json::array();
  for (int c : run.conditions()) states.push_back(json::parse(run.procedure_state(c).dump()));
  return {{"seed", std::to_string(seed)}, {"trials", trials}, {"rows", rows}, {"states", states}};
}

json session_case(const json& forced_choice, const std::string& subject, int session,
                  const std::string& observer) {
  json page = page_study(forced_choice);
  page["model"] = page_model();
  return {{"page", page},
          {"subject", subject},
          {"session", session},
          {"observer", observer},
          {"app", native_session(page, subject, session, observer)}};
}

TEST(ChoiceEngine, TheWebAssemblySessionIsTheAppsTrialForTrial) {
  json cases = json::array();
  cases.push_back(session_case(
      {{"n_afc", 2},
       {"practice_trials", 3},
       {"procedure",
        {{"type", "constant"}, {"lambdas", {0.1, 0.2, 0.4, 0.8}}, {"repetitions", 3}}}},
      "P01", 1, "weibull:0.3,3,7"));
  cases.push_back(session_case(
      {{"n_afc", 3},
       {"layout", "temporal"},
       {"procedure",
        {{"type", "staircase"}, {"startVal", 0.8}, {"stepSizes", {4, 2, 1}}, {"nTrials", 20}}}},
      "sim-2", 3, "weibull:0.25,2.5,11"));
  cases.push_back(session_case({{"n_afc", 4},
                                {"procedure",
                                 {{"type", "quest"},
                                  {"tGuess", -0.7},
                                  {"tGuessSd", 0.6},
                                  {"pThreshold", 0.82},
                                  {"beta", 3.5},
                                  {"delta", 0.01},
                                  {"gamma", 0.25},
                                  {"nTrials", 25}}}},
                               "P03", 2, "weibull:0.4,3,5"));
  cases.push_back(
      session_case({{"n_afc", 2},
                    {"seed", 99},
                    {"conditions", {{{"scene", "cube"}, {"method", "usm3d"}, {"sigma", 0.02}}}},
                    {"procedure",
                     {{"type", "questplus"},
                      {"trials", 30},
                      {"param_domain",
                       {{"threshold", {-1.3, -1.1, -0.9, -0.7, -0.5, -0.3, -0.1, 0.1}},
                        {"slope", {2, 3.5, 5}},
                        {"lower_asymptote", 0.5},
                        {"lapse_rate", {0, 0.02}}}}}}},
                   "P04", 1, "weibull:0.2,3,3"));
  cases.push_back(session_case(
      {{"n_afc", 2},
       {"procedure",
        {{"type", "constant"}, {"lambdas", {0.05, 0.1, 0.2, 0.4}}, {"repetitions", 4}}}},
      "P05", 1, "model:5"));
  testing::TempDir dir;
  testing::write_file(dir / "cases.json", cases.dump());
  const auto run =
      testing::run_program("bash -c", "'cd " + testing::source_dir().string() +
                                          " && COUNTERSHADE_WEB_ENGINE=" COUNTERSHADE_WEB_ENGINE
                                          " node web/tools/check-choice.mjs " +
                                          (dir / "cases.json").string() + "'");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("5 sessions"), std::string::npos) << run.output;
}

}  // namespace
}  // namespace countershade::web_engine
