// The adjustment study's logic for the exported page, compiled to WebAssembly: the session seed,
// the plan, the procedure and the simulated observer are the app's own code (src/adjust,
// src/runtime), so the browser and the app cannot drift apart. The page talks to them through
// web/engine.js. Structured values cross as JSON text; keys and phases as their names.

#include <emscripten/bind.h>

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "adjust/procedure.h"
#include "adjust/simulated_observer.h"
#include "observer/model_response.h"
#include "runtime/study.h"
#include "web_engine/javascript_errors.h"
#include "web_engine/page_model.h"
#include "web_engine/page_study.h"

namespace countershade::web_engine {
namespace {

using adjust::Answer;
using adjust::PastAnswer;
using adjust::Procedure;
using adjust::SimulatedObserver;
using adjust::Trial;
using runtime::Condition;
using runtime::Key;
using runtime::Study;
using json = nlohmann::json;

const char* const kKeyNames[] = {"up",     "down", "left", "right", "enter", "backspace",
                                 "escape", "q",    "1",    "2",     "3",     "4"};
const char* const kPhaseNames[] = {"instructions", "practice_done", "question",
                                   "paused",       "finished",      "quit"};

std::optional<Key> key_named(const std::string& name) {
  for (int k = 0; k < int(std::size(kKeyNames)); ++k)
    if (name == kKeyNames[k]) return Key(k);
  return std::nullopt;
}

json trial_json(const Trial& t) {
  return {{"number", t.number},
          {"practice", t.practice},
          {"condition", t.condition},
          {"repetition", t.repetition},
          {"side", procedures::side_name(t.side)},
          {"start", {t.start_index[0], t.start_index[1], t.start_index[2]}}};
}

Trial trial_of(const json& j) {
  Trial t;
  t.number = j.at("number").get<int>();
  t.practice = j.at("practice").get<bool>();
  t.condition = j.at("condition").get<int>();
  t.repetition = j.at("repetition").get<int>();
  t.side = side_named(j.at("side").get<std::string>());
  for (int q = 0; q < kQuestionCount; ++q) t.start_index[q] = j.at("start").at(q).get<int>();
  return t;
}

// The seed of a subject's session, as decimal text (JavaScript numbers hold 53 bits).
std::string session_seed(const std::string& study_seed, const std::string& subject, int session) {
  return errors_to_javascript([&] {
    return std::to_string(runtime::session_seed(std::stoull(study_seed), subject, session));
  });
}

// The plan of a subject's session for the page's study: a JSON array of trials.
std::string plan_of(const json& page, const std::string& subject, int session) {
  json plan = json::array();
  for (const Trial& t : page_plan(page, subject, session)) plan.push_back(trial_json(t));
  return plan.dump();
}

std::string plan_session(const std::string& page_json, const std::string& subject, int session) {
  return errors_to_javascript([&] { return plan_of(json::parse(page_json), subject, session); });
}

}  // namespace

// The procedure of one session, over the page's study and a plan (plan_session's, or a test's).
class AdjustmentProcedure {
 public:
  AdjustmentProcedure(const std::string& page_json, const std::string& plan_json)
      : page_(errors_to_javascript([&] { return json::parse(page_json); })),
        study_(errors_to_javascript([&] { return study_from_page(page_); })),
        procedure_(errors_to_javascript([&] { return make(page_, study_, plan_json); })) {}

  std::string phase() const { return kPhaseNames[int(procedure_.phase())]; }
  bool done() const { return procedure_.done(); }
  int trial_index() const { return procedure_.trial_index(); }
  int question() const { return int(procedure_.question()); }
  int lambda_index() const { return procedure_.lambda_index(); }
  int real_trial_count() const { return procedure_.real_trial_count(); }

  // A key press at a time in seconds; the answer it confirmed as JSON, or "".
  std::string press(const std::string& key, double time_s) {
    const auto k = key_named(key);
    if (!k) return "";
    const std::optional<Answer> a = procedure_.press(*k, time_s);
    if (!a) return "";
    return json{{"trialIndex", a->trial_index},   {"question", question_name(a->question)},
                {"lambdaIndex", a->lambda_index}, {"startIndex", a->start_index},
                {"keypresses", a->n_keypresses},  {"rt", a->rt_s},
                {"revision", a->revision}}
        .dump();
  }
  void release(const std::string& key, double time_s) {
    if (const auto k = key_named(key)) procedure_.release(*k, time_s);
  }
  void tick(double time_s) { procedure_.tick(time_s); }

  // Continues a session from its stored answers: [[plan index, question, λ index, revision], …].
  void resume(const std::string& answered_json) {
    std::map<std::pair<int, int>, PastAnswer> answered;
    errors_to_javascript([&] {
      for (const json& a : json::parse(answered_json))
        answered[{a.at(0).get<int>(), a.at(1).get<int>()}] = {a.at(2).get<int>(),
                                                              a.at(3).get<int>()};
    });
    procedure_.resume(answered);
  }

  const Procedure& procedure() const { return procedure_; }
  const Study& study() const { return study_; }
  const json& page() const { return page_; }

 private:
  static Procedure make(const json& page, const Study& study, const std::string& plan_json) {
    std::vector<Trial> plan;
    for (const json& t : json::parse(plan_json)) plan.push_back(trial_of(t));
    procedures::RepeatTiming timing;
    timing.repeat_delay_s = page.at("timing").at("delay").get<double>();
    timing.repeat_interval_s = page.at("timing").at("interval").get<double>();
    return Procedure(study.conditions, std::move(plan), timing);
  }

  json page_;
  Study study_;
  Procedure procedure_;
};

// The app's simulated observer watching one procedure: simulated:SEED, or model:SEED answering
// from the prediction the page was exported with (export-web --model-ppd).
class AdjustmentObserver {
 public:
  AdjustmentObserver(const std::string& spec, const AdjustmentProcedure& procedure)
      : procedure_(procedure),
        observer_(errors_to_javascript([&] { return observer_of(spec, procedure); })) {}

  // The key it presses now, or "" (a press and its release come together).
  std::string key(double time_s) {
    const auto events = observer_.act(procedure_.procedure(), time_s);
    return events.empty() ? "" : kKeyNames[int(events.front().key)];
  }

 private:
  static SimulatedObserver observer_of(const std::string& spec,
                                       const AdjustmentProcedure& procedure) {
    const auto model = observer::parse_model_observer(spec);
    if (!model) return SimulatedObserver(adjust::parse_observer_spec(spec), procedure.study());
    SimulatedObserver::PredictedLevels levels;
    for (const auto& c : predicted_page_conditions(procedure.page(), *model))
      levels.push_back(c.lambda_at);
    return SimulatedObserver(model->seed, procedure.study(), 0.02, std::move(levels));
  }

  const AdjustmentProcedure& procedure_;
  SimulatedObserver observer_;
};

EMSCRIPTEN_BINDINGS(countershade_adjustment) {
  using namespace emscripten;
  function("sessionSeed", &session_seed);
  function("planSession", &plan_session);
  class_<AdjustmentProcedure>("AdjustmentProcedure")
      .constructor<std::string, std::string>()
      .function("phase", &AdjustmentProcedure::phase)
      .function("done", &AdjustmentProcedure::done)
      .function("trialIndex", &AdjustmentProcedure::trial_index)
      .function("question", &AdjustmentProcedure::question)
      .function("lambdaIndex", &AdjustmentProcedure::lambda_index)
      .function("realTrialCount", &AdjustmentProcedure::real_trial_count)
      .function("press", &AdjustmentProcedure::press)
      .function("release", &AdjustmentProcedure::release)
      .function("tick", &AdjustmentProcedure::tick)
      .function("resume", &AdjustmentProcedure::resume);
  class_<AdjustmentObserver>("AdjustmentObserver")
      .constructor<std::string, const AdjustmentProcedure&>()
      .function("key", &AdjustmentObserver::key);
}

}  // namespace countershade::web_engine
