#pragma once
// What one session's rows may be: its subject, session and set, and, in the adjustment study, an
// answer to one of the questions of one of the trials its plan has, as the plan has that trial.

#include <map>
#include <string>
#include <vector>

#include "serve/study_folder.h"

namespace countershade::serve {

class SessionPlan {
 public:
  // Plans the session as the page and the app do (web_engine::page_plan).
  SessionPlan(const StudyFolder& folder, std::string subject, int session);

  // Checks a row's fields (one per folder.columns). Returns the answer it gives ("TRIAL:QUESTION"
  // in the adjustment study, "" where the study has no fixed plan). Throws Refusal: 403 for a row
  // of another subject, session or set, 422 for an answer the plan does not have.
  std::string check(const std::vector<std::string>& fields) const;

  // The answers a completed session has given (every question of every real trial); 0 where the
  // study's procedure decides the number of trials as it goes.
  int answers_expected() const { return answers_expected_; }

 private:
  struct Expected {
    int condition = 0;
    std::string repetition, side;
  };
  const std::string& field(const std::vector<std::string>& fields, const char* column) const;
  void check_condition(const std::vector<std::string>& fields, int condition) const;
  std::string check_adjustment(const std::vector<std::string>& fields) const;

  const StudyFolder& folder_;
  std::string subject_;
  int session_;
  std::map<std::string, int> column_;       // column name → index
  std::map<std::string, Expected> trials_;  // real trials by number (as text)
  int answers_expected_ = 0;
};

}  // namespace countershade::serve
