// The forced-choice study's logic for the exported page, compiled to WebAssembly: the app's
// session of trials (src/forced_choice/choice_run.cpp) with the procedure plug-ins of
// src/procedures (constant stimuli, staircase, QUEST, QUEST+) and the simulated observer. The page
// shows what current() says and feeds answer(); after a reload it replays the stored answers
// through answer(), so every procedure's state equals that of an uninterrupted run.

#include <emscripten/bind.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "forced_choice/choice_observer.h"
#include "forced_choice/choice_row.h"
#include "forced_choice/choice_run.h"
#include "runtime/study.h"
#include "web_engine/javascript_errors.h"
#include "web_engine/page_model.h"
#include "web_engine/page_study.h"

namespace countershade::web_engine {

using forced_choice::ChoiceConfig;
using forced_choice::ChoiceRun;
using forced_choice::ChoiceTrial;
using json = nlohmann::json;

// One participant's forced-choice session over the page's study, whose "forced_choice" is the
// experiment's block as written.
class ChoiceSession {
 public:
  ChoiceSession(const std::string& page_json, const std::string& subject, int session)
      : page_(errors_to_javascript([&] { return json::parse(page_json); })),
        study_(errors_to_javascript([&] { return study_from_page(page_); })),
        config_(errors_to_javascript([&] {
          return procedures::parse_choice_config(page_.at("forced_choice"), "study.js",
                                                 "forced_choice");
        })),
        seed_(errors_to_javascript([&] {
          return config_.seed ? runtime::session_seed(*config_.seed, subject, session)
                              : page_session_seed(page_, subject, session);
        })),
        run_(errors_to_javascript([&] { return ChoiceRun(study_, config_, seed_); })),
        who_{subject, session, page_.contains("set") ? page_["set"].value("sha256", "") : ""} {}

  std::string session_seed() const { return std::to_string(seed_); }
  // The trial to show now as JSON, or "null" once the session is finished.
  std::string current() const {
    const auto& t = run_.current();
    if (!t) return "null";
    return json{{"number", t->number},
                {"practice", t->practice},
                {"condition", t->condition},
                {"condition_trial", t->condition_trial},
                {"requested", t->intensity.requested},
                {"lambda_index", t->lambda_index},
                {"lambda", t->lambda},
                {"target", t->target}}
        .dump();
  }
  bool ready() const { return run_.ready(); }
  // The answer to the current trial (a position or interval, 0-based); whether it was correct.
  bool answer(int response) {
    return errors_to_javascript([&] {
      if (!run_.current()) throw std::invalid_argument("the session is finished");
      if (response < 0 || response >= config_.n_afc)
        throw std::invalid_argument("an answer is a position from 0 to n_afc - 1");
      return run_.answer(response);
    });
  }
  // Answers the current trial and gives {correct, row}: the trials CSV's fields as the app writes
  // them (an empty row for a practice trial, which is not recorded).
  std::string answer_with_row(int response, double rt_s, const std::string& time_utc) {
    return errors_to_javascript([&] {
      const ChoiceTrial t = run_.current().value();
      const bool correct = answer(response);
      const auto row = t.practice ? std::vector<std::string>{}
                                  : forced_choice::choice_row(study_, config_, who_, t, response,
                                                              correct, rt_s, time_utc);
      return json{{"correct", correct}, {"row", row}}.dump();
    });
  }
  // The row of an answer to the current trial that does not count (a temporal trial shown with a
  // mistimed interval): the session stays at this trial, which is shown again.
  std::string row_without_answer(int response, double rt_s, const std::string& time_utc) const {
    return errors_to_javascript([&] {
      const ChoiceTrial t = run_.current().value();
      return json(forced_choice::choice_row(study_, config_, who_, t, response,
                                            response == t.target, rt_s, time_utc))
          .dump();
    });
  }
  // Continues a session from its recorded rows (a JSON array of rows of fields), as the app's
  // resume does: practice is skipped and each row must be the trial the session shows next.
  void replay(const std::string& rows_json) {
    errors_to_javascript([&] {
      const auto rows = json::parse(rows_json).get<std::vector<std::vector<std::string>>>();
      forced_choice::replay_choice_rows(run_, rows, study_, config_.n_afc, [](size_t r) {
        return "stored row " + std::to_string(r + 1);
      });
    });
  }
  bool finished() const { return run_.finished(); }
  bool in_practice() const { return run_.in_practice(); }
  int real_trials_done() const { return run_.real_trials_done(); }
  // The page's study (for its model observer's prediction).
  const json& page() const { return page_; }
  // The study's conditions that have a procedure, and one's state after its last answer (JSON).
  std::string conditions() const { return json(run_.conditions()).dump(); }
  std::string procedure_state(int condition) const {
    return errors_to_javascript([&] { return run_.procedure_state(condition).dump(); });
  }

 private:
  json page_;
  runtime::Study study_;
  ChoiceConfig config_;
  uint64_t seed_;
  ChoiceRun run_;
  forced_choice::ChoiceRowContext who_;
};

// The app's simulated observer: weibull:ALPHA,BETA,SEED, or model:SEED answering from the
// prediction the page was exported with (export-web --model-ppd).
class ChoiceObserver {
 public:
  ChoiceObserver(const std::string& spec, const ChoiceSession& session)
      : observer_(
            errors_to_javascript([&] { return page_choice_observer(session.page(), spec); })) {}

  // The answer to real trial `number` (practice: 0, and the practice trial's index) of
  // `condition` (a model observer answers per condition).
  int respond_to(int condition, int number, int practice_index, double lambda, int target,
                 int n_afc) const {
    return observer_.respond(number, practice_index, lambda, target, n_afc, condition);
  }
  double delay() const { return observer_.delay_s; }

 private:
  forced_choice::ChoiceObserver observer_;
};

// The trials CSV's columns, in order (JSON).
std::string choice_columns() { return json(forced_choice::choice_columns()).dump(); }

EMSCRIPTEN_BINDINGS(countershade_forced_choice) {
  using namespace emscripten;
  function("choiceColumns", &choice_columns);
  class_<ChoiceSession>("ChoiceSession")
      .constructor<std::string, std::string, int>()
      .function("sessionSeed", &ChoiceSession::session_seed)
      .function("current", &ChoiceSession::current)
      .function("ready", &ChoiceSession::ready)
      .function("answer", &ChoiceSession::answer)
      .function("answerWithRow", &ChoiceSession::answer_with_row)
      .function("rowWithoutAnswer", &ChoiceSession::row_without_answer)
      .function("replay", &ChoiceSession::replay)
      .function("finished", &ChoiceSession::finished)
      .function("inPractice", &ChoiceSession::in_practice)
      .function("realTrialsDone", &ChoiceSession::real_trials_done)
      .function("conditions", &ChoiceSession::conditions)
      .function("procedureState", &ChoiceSession::procedure_state);
  class_<ChoiceObserver>("ChoiceObserver")
      .constructor<std::string, const ChoiceSession&>()
      .function("respondTo", &ChoiceObserver::respond_to)
      .function("delay", &ChoiceObserver::delay);
}

}  // namespace countershade::web_engine
