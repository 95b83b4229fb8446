#pragma once
// The method-of-adjustment procedure as a plain state machine (docs/adjustment-study.md). It knows
// nothing about windows or files: the presenter feeds it key events with their times and draws
// what it says; the recorder writes the answers it returns. Tests drive it directly.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "formats/responses.h"
#include "procedures/adjustment_block.h"
#include "runtime/key_script.h"
#include "runtime/study.h"

namespace countershade::adjust {

// The block's settings, read with the experiment (procedures/adjustment_block.h).
using procedures::PlanSettings;
using procedures::RepeatTiming;
using procedures::Side;
using procedures::side_name;
using procedures::StartMode;
// The study's conditions and the keys (src/runtime).
using runtime::Condition;
using runtime::Key;

struct Trial {
  int number = 0;  // 1-based position among the real trials; 0 for practice trials
  bool practice = false;
  int condition = 0;        // index into the condition list
  int repetition = 1;       // 1-based
  Side side = Side::right;  // side of the enhanced image
  int start_index[kQuestionCount] = {0, 0, 0};
};

// The full trial list of a session: practice trials first, then every condition × repetition in a
// seeded random order. Counterbalancing alternates a condition's side over its repetitions, and
// balances the first side over the conditions. The same settings always give the same plan.
std::vector<Trial> plan_trials(const std::vector<Condition>& conditions,
                               const PlanSettings& settings);

// A confirmed answer, returned by the procedure for the recorder to write.
struct Answer {
  int trial_index = 0;  // index into the plan
  Question question = Question::low;
  int lambda_index = 0;
  int start_index = 0;
  int n_keypresses = 0;  // arrow-key presses for this answer (auto-repeat steps not counted)
  double rt_s = 0;       // from the question appearing to Enter
  int revision = 0;      // 0 for the first answer; +1 each time the observer went back to it
};

// What the procedure remembers about an answered question, e.g. from a session being resumed.
struct PastAnswer {
  int lambda_index = 0;
  int revision = 0;
};

class Procedure {
 public:
  enum class Phase {
    instructions,   // the welcome text (or "welcome back" after a resume); Enter starts
    practice_done,  // between the practice and the real trials; Enter continues
    question,       // a stimulus pair is shown and λ is adjusted
    paused,         // Esc: Enter or Esc resumes, Q quits
    finished,       // every question answered
    quit,           // the observer chose "quit and save"
  };

  Procedure(std::vector<Condition> conditions, std::vector<Trial> plan, RepeatTiming timing = {});

  // Continue a session: skips the practice trials and every question in `answered` (keyed by
  // plan index and question), and starts at the first unanswered question in plan order.
  // Going back to an answered question later shows its recorded λ and raises its revision.
  void resume(const std::map<std::pair<int, int>, PastAnswer>& answered);

  // Key events. GLFW's own key repeat is not used: a held key repeats through tick().
  // press() returns the answer when the key confirmed one.
  std::optional<Answer> press(Key key, double time_s);
  void release(Key key, double time_s);
  void tick(double time_s);

  Phase phase() const { return phase_; }
  bool done() const { return phase_ == Phase::finished || phase_ == Phase::quit; }
  const std::vector<Trial>& plan() const { return plan_; }
  const std::vector<Condition>& conditions() const { return conditions_; }
  int trial_index() const { return trial_; }
  const Trial& trial() const { return plan_[size_t(trial_)]; }
  const Condition& condition() const { return conditions_[size_t(trial().condition)]; }
  Question question() const { return Question(question_); }
  int lambda_index() const { return index_; }
  int real_trial_count() const;
  // The number of real questions answered at least once (for progress display and the sidecar).
  int answered_count() const { return int(answered_.size()); }
  // Whether an arrow key is being held (and so auto-repeating), for frame-time statistics.
  bool key_held() const { return held_.has_value(); }

 private:
  void enter_question(int trial, int question, double time_s);
  void press_between_questions(Key key, double time_s);  // instructions, pause, end
  Answer confirm(double time_s);                         // Enter on a question: its answer
  void step(int direction);
  void advance(double time_s);
  bool is_answered(int trial, int question) const;

  std::vector<Condition> conditions_;
  std::vector<Trial> plan_;
  RepeatTiming timing_;
  Phase phase_ = Phase::instructions, paused_from_ = Phase::instructions;
  int trial_ = 0, question_ = 0, index_ = 0;
  int keypresses_ = 0;
  double shown_at_ = 0, paused_at_ = 0;
  std::optional<Key> held_;
  double next_repeat_ = 0;
  std::map<std::pair<int, int>, PastAnswer> answered_;  // real trials only
  std::map<std::pair<int, int>, PastAnswer> practice_answers_;
};

}  // namespace countershade::adjust
