#include "adjust/procedure.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "core/random.h"

namespace countershade::adjust {

namespace {

// Streams of the session seed, kept apart so adding practice trials does not change the order.
enum : uint64_t {
  kStreamOrder = 101,
  kStreamSide = 102,
  kStreamStart = 103,
  kStreamPractice = 104
};

// Fisher–Yates with counter-based draws: the order depends on the seed alone.
template <typename T>
void seeded_shuffle(std::vector<T>& items, uint64_t seed, uint64_t stream) {
  SampleStream random(seed, stream, 0, 0);
  for (size_t i = items.size(); i > 1; --i) {
    size_t j = std::min(size_t(random.next() * double(i)), i - 1);
    std::swap(items[i - 1], items[j]);
  }
}

int draw_start(const Condition& c, const PlanSettings& s, uint64_t trial_key, int question) {
  if (s.start == StartMode::zero) return 0;
  SampleStream random(s.seed, kStreamStart, trial_key, uint64_t(question));
  return std::min(int(random.next() * c.grid_size), c.grid_size - 1);
}

}  // namespace

namespace {

// Every condition × repetition, in a seeded random order. Counterbalanced, the first side of each
// condition alternates left/right over the conditions, then is shuffled (the two sides differ in
// count by at most one), and it flips with every repetition.
std::vector<Trial> real_trials(size_t n, const PlanSettings& s) {
  std::vector<Side> first_side(n);
  for (size_t c = 0; c < n; ++c) first_side[c] = c % 2 == 0 ? Side::left : Side::right;
  seeded_shuffle(first_side, s.seed, kStreamSide);
  std::vector<Trial> real;
  for (int r = 1; r <= s.repetitions; ++r)
    for (size_t c = 0; c < n; ++c) {
      Trial t;
      t.condition = int(c);
      t.repetition = r;
      const bool flip = (r - 1) % 2 == 1;
      t.side = s.side != Side::counterbalanced
                   ? s.side
                   : ((first_side[c] == Side::left) != flip ? Side::left : Side::right);
      real.push_back(t);
    }
  seeded_shuffle(real, s.seed, kStreamOrder);
  return real;
}

// The practice trials: conditions in a seeded order, sides alternating when counterbalanced.
std::vector<Trial> practice_trials(const std::vector<Condition>& conditions,
                                   const PlanSettings& s) {
  std::vector<int> pick = s.practice_conditions;
  if (pick.empty()) {
    pick.resize(conditions.size());
    std::iota(pick.begin(), pick.end(), 0);
  }
  seeded_shuffle(pick, s.seed, kStreamPractice);
  std::vector<Trial> practice;
  for (int p = 0; p < s.practice_trials; ++p) {
    Trial t;
    t.practice = true;
    t.condition = pick[size_t(p) % pick.size()];
    t.side = s.side == Side::counterbalanced ? (p % 2 == 0 ? Side::left : Side::right) : s.side;
    for (int q = 0; q < kQuestionCount; ++q)
      t.start_index[q] =
          draw_start(conditions[size_t(t.condition)], s, (1ull << 40) + uint64_t(p), q);
    practice.push_back(t);
  }
  return practice;
}

}  // namespace

std::vector<Trial> plan_trials(const std::vector<Condition>& conditions, const PlanSettings& s) {
  if (conditions.empty()) throw std::invalid_argument("a study needs at least one condition");
  if (s.repetitions < 1) throw std::invalid_argument("repetitions must be at least 1");
  const std::vector<Trial> real = real_trials(conditions.size(), s);
  std::vector<Trial> plan = practice_trials(conditions, s);
  for (size_t i = 0; i < real.size(); ++i) {
    Trial t = real[i];
    t.number = int(i) + 1;
    for (int q = 0; q < kQuestionCount; ++q)
      t.start_index[q] = draw_start(conditions[size_t(t.condition)], s, uint64_t(t.number), q);
    plan.push_back(t);
  }
  return plan;
}

Procedure::Procedure(std::vector<Condition> conditions, std::vector<Trial> plan,
                     RepeatTiming timing)
    : conditions_(std::move(conditions)), plan_(std::move(plan)), timing_(timing) {
  if (plan_.empty()) throw std::invalid_argument("empty trial plan");
  for (const auto& t : plan_)
    if (t.condition < 0 || size_t(t.condition) >= conditions_.size())
      throw std::invalid_argument("trial refers to an unknown condition");
  index_ = plan_[0].start_index[0];
}

int Procedure::real_trial_count() const {
  return int(std::count_if(plan_.begin(), plan_.end(), [](const Trial& t) { return !t.practice; }));
}

bool Procedure::is_answered(int trial, int question) const {
  return answered_.count({trial, question}) > 0;
}

void Procedure::resume(const std::map<std::pair<int, int>, PastAnswer>& answered) {
  answered_ = answered;
  phase_ = Phase::finished;
  for (int t = 0; t < int(plan_.size()); ++t) {
    if (plan_[size_t(t)].practice) continue;
    for (int q = 0; q < kQuestionCount; ++q)
      if (!is_answered(t, q)) {
        trial_ = t;
        question_ = q;
        phase_ = Phase::instructions;
        return;
      }
  }
}

void Procedure::enter_question(int trial, int question, double time_s) {
  trial_ = trial;
  question_ = question;
  const Trial& t = plan_[size_t(trial)];
  const auto& past = t.practice ? practice_answers_ : answered_;
  auto it = past.find({trial, question});
  index_ = it != past.end() ? it->second.lambda_index : t.start_index[question];
  index_ = std::clamp(index_, 0, conditions_[size_t(t.condition)].grid_size - 1);
  keypresses_ = 0;
  shown_at_ = time_s;
  held_.reset();
  phase_ = Phase::question;
}

void Procedure::step(int direction) {
  index_ = std::clamp(index_ + direction, 0, condition().grid_size - 1);
}

void Procedure::advance(double time_s) {
  if (question_ + 1 < kQuestionCount) {
    enter_question(trial_, question_ + 1, time_s);
    return;
  }
  int next = trial_ + 1;
  if (next >= int(plan_.size())) {
    phase_ = Phase::finished;
    held_.reset();
    return;
  }
  if (plan_[size_t(trial_)].practice && !plan_[size_t(next)].practice) {
    trial_ = next;
    question_ = 0;
    held_.reset();
    phase_ = Phase::practice_done;
    return;
  }
  enter_question(next, 0, time_s);
}

void Procedure::press_between_questions(Key key, double time_s) {
  switch (phase_) {
    case Phase::instructions:
    case Phase::practice_done:
      if (key == Key::enter)
        enter_question(trial_, question_, time_s);
      else if (key == Key::escape) {
        paused_from_ = phase_;
        phase_ = Phase::paused;
      }
      return;
    case Phase::paused:
      if (key == Key::enter || key == Key::escape) {
        phase_ = paused_from_;
        // The time spent paused does not count towards the response time.
        if (phase_ == Phase::question) shown_at_ += time_s - paused_at_;
      } else if (key == Key::quit) {
        phase_ = Phase::quit;
      }
      return;
    case Phase::finished:
    case Phase::quit:
    case Phase::question:
      return;
  }
}

Answer Procedure::confirm(double time_s) {
  Answer a;
  a.trial_index = trial_;
  a.question = Question(question_);
  a.lambda_index = index_;
  a.start_index = trial().start_index[question_];
  a.n_keypresses = keypresses_;
  a.rt_s = time_s - shown_at_;
  auto& past = trial().practice ? practice_answers_ : answered_;
  auto it = past.find({trial_, question_});
  a.revision = it == past.end() ? 0 : it->second.revision + 1;
  past[{trial_, question_}] = PastAnswer{index_, a.revision};
  advance(time_s);
  return a;
}

std::optional<Answer> Procedure::press(Key key, double time_s) {
  if (phase_ != Phase::question) {
    press_between_questions(key, time_s);
    return std::nullopt;
  }
  switch (key) {
    case Key::up:
    case Key::right:
    case Key::down:
    case Key::left:
      step(key == Key::up || key == Key::right ? +1 : -1);
      ++keypresses_;
      held_ = key;
      next_repeat_ = time_s + timing_.repeat_delay_s;
      return std::nullopt;
    case Key::enter:
      return confirm(time_s);
    case Key::backspace:
      if (question_ > 0) enter_question(trial_, question_ - 1, time_s);
      return std::nullopt;
    case Key::escape:
      held_.reset();
      paused_from_ = Phase::question;
      phase_ = Phase::paused;
      paused_at_ = time_s;
      return std::nullopt;
    case Key::quit:
    case Key::one:
    case Key::two:
    case Key::three:
    case Key::four:
      return std::nullopt;
  }
  return std::nullopt;
}

void Procedure::release(Key key, double time_s) {
  if (held_ && *held_ == key) {
    tick(time_s);  // the repeats that fell due while the key was still down
    held_.reset();
  }
}

void Procedure::tick(double time_s) {
  if (phase_ != Phase::question || !held_) return;
  const int direction = *held_ == Key::up || *held_ == Key::right ? +1 : -1;
  while (time_s >= next_repeat_) {
    step(direction);
    next_repeat_ += timing_.repeat_interval_s;
  }
}

}  // namespace countershade::adjust
