#pragma once
// What one session's rows may be: its subject, session and set, and the next answer its plan has.
// In the adjustment study, an answer to one of the questions of one of the planned trials, as the
// plan has that trial. In the forced-choice study, the trial the session shows next: the server
// runs the app's session of trials alongside the page (forced_choice::ChoiceRun, the same code),
// moving it on with each row it stores, so it knows each next trial and when the session is done.

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "forced_choice/choice_run.h"
#include "serve/study_folder.h"

namespace countershade::serve {

class SessionPlan {
 public:
  // Plans the session as the page and the app do (web_engine::page_plan, or the forced-choice
  // run with its practice trials answered).
  SessionPlan(const StudyFolder& folder, std::string subject, int session);
  ~SessionPlan();

  // Checks the next row's fields (one per folder.columns). Returns the answer it gives
  // ("TRIAL:QUESTION" in the adjustment study, the trial number in the forced-choice study).
  // Throws Refusal: 403 for a row of another subject, session or set, 422 for a row that is not
  // the plan's.
  std::string check(const std::vector<std::string>& fields) const;

  // A checked row is stored: the forced-choice run moves on to its next trial (unless the row
  // records a mistimed interval, whose trial is shown again). Returns whether the session is
  // now complete.
  bool record(const std::vector<std::string>& fields);

  // The answers a completed adjustment session has given (every question of every real trial);
  // 0 in the forced-choice study, whose procedures decide the number of trials as they go.
  int answers_expected() const { return answers_expected_; }

  // Held while a row of the session is checked, stored and recorded.
  std::mutex& mutex() { return mutex_; }
  // Rows stored in the session: the index the next new row has.
  long rows_stored = 0;

 private:
  struct Expected {
    int condition = 0;
    std::string repetition, side;
  };
  struct Choice;  // the forced-choice study and its run
  const std::string& field(const std::vector<std::string>& fields, const char* column) const;
  void check_condition(const std::vector<std::string>& fields, int condition) const;
  std::string check_adjustment(const std::vector<std::string>& fields) const;
  std::string check_choice(const std::vector<std::string>& fields) const;

  const StudyFolder& folder_;
  std::string subject_;
  int session_;
  std::map<std::string, int> column_;       // column name → index
  std::map<std::string, Expected> trials_;  // real trials by number (as text)
  int answers_expected_ = 0;
  std::unique_ptr<Choice> choice_;
  std::mutex mutex_;
};

}  // namespace countershade::serve
