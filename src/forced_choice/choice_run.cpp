#include "forced_choice/choice_run.h"

#include <algorithm>
#include <numeric>
#include <set>

#include "core/error.h"
#include "core/number_format.h"
#include "core/random.h"

namespace countershade::forced_choice {
namespace {

// Streams of the session seed, apart from the procedures' own.
enum : uint64_t { kStreamCondition = 301, kStreamTarget = 302, kStreamPractice = 303 };

std::vector<int> select(const runtime::Study& study, const std::vector<ConditionSelection>& wanted,
                        const std::string& source, const std::string& key) {
  std::vector<int> out;
  for (size_t w = 0; w < wanted.size(); ++w) {
    const auto& c = study.conditions;
    const auto it = std::find_if(c.begin(), c.end(), [&](const runtime::Condition& x) {
      return wanted[w].names(x.scene, x.method, x.sigma);
    });
    if (it == c.end())
      throw_input_error(source + key + "[" + std::to_string(w) + "]",
                        "no condition " + wanted[w].scene + " / " + wanted[w].method + " / σ " +
                            std::to_string(wanted[w].sigma) + " in the set");
    out.push_back(int(it - c.begin()));
  }
  return out;
}

// The conditions a session runs: those the block lists, else every condition of the set.
std::vector<int> session_conditions(const runtime::Study& study, const ChoiceConfig& config) {
  std::vector<int> out = select(study, config.conditions, config.source, "conditions");
  if (out.empty()) {
    out.resize(study.conditions.size());
    std::iota(out.begin(), out.end(), 0);
  }
  return out;
}

// Every condition given its own procedure must be one the session runs: a typo there would
// otherwise leave the condition on the block's procedure without a word.
void check_condition_procedures(const runtime::Study& study, const ChoiceConfig& config,
                                const std::vector<int>& running) {
  for (size_t k = 0; k < config.condition_procedures.size(); ++k) {
    const ConditionSelection& wanted = config.condition_procedures[k].condition;
    const bool runs = std::any_of(running.begin(), running.end(), [&](int i) {
      const auto& c = study.conditions[size_t(i)];
      return wanted.names(c.scene, c.method, c.sigma);
    });
    if (!runs)
      throw_input_error(config.source + "condition_procedures[" + std::to_string(k) + "]",
                        "no condition " + wanted.scene + " / " + wanted.method + " / σ " +
                            format_value(wanted.sigma) + " among the session's conditions");
  }
}

ChoiceGrid grid_of(const runtime::Study& study, int condition) {
  ChoiceGrid g;
  const int size = int(study.condition_images[size_t(condition)].size()) - 1;
  for (int i = 0; i < size; ++i)
    if (study.lambda(i) > 0) {
      g.lambdas.push_back(study.lambda(i));
      g.indices.push_back(i);
    }
  return g;
}

// The target of a condition's k-th trial (0-based): every block of n trials shows each position
// once, in a seeded order.
int balanced_target(uint64_t seed, int condition, int k, int n) {
  std::vector<int> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  SampleStream random(seed, kStreamTarget, uint64_t(condition), uint64_t(k / n));
  for (size_t i = order.size(); i > 1; --i)
    std::swap(order[i - 1], order[std::min(size_t(random.next() * double(i)), i - 1)]);
  return order[size_t(k % n)];
}

}  // namespace

std::optional<std::string> procedure_memory_problem(const runtime::Study& study,
                                                    const ChoiceConfig& config, double limit) {
  const std::vector<int> conditions = session_conditions(study, config);
  double need = 0;
  std::set<std::string> shared;  // each shared part counts once
  for (int c : conditions) {
    const auto& condition = study.conditions[size_t(c)];
    const auto& settings =
        *config.procedure_of(condition.scene, condition.method, condition.sigma).settings;
    for (const auto& part : settings.memory(grid_of(study, c)))
      if (part.shared.empty() || shared.insert(part.shared).second) need += part.bytes;
  }
  if (need <= limit) return std::nullopt;
  const auto gib = [](double bytes) { return format_value(round_to(bytes / (1 << 30), 2)); };
  return "the procedures of the session's " + std::to_string(conditions.size()) +
         " conditions, all started at once, would hold " + gib(need) + " GiB, more than the " +
         gib(limit) + " GiB they may take";
}

ChoiceRun::ChoiceRun(const runtime::Study& study, const ChoiceConfig& config, uint64_t seed)
    : study_(study), config_(config), seed_(seed) {
  conditions_ = session_conditions(study, config);
  practice_conditions_ =
      select(study, config.practice_conditions, config.source, "practice_conditions");
  if (practice_conditions_.empty())
    for (int c : conditions_)
      if (study.changes_with_lambda(c)) practice_conditions_.push_back(c);
  if (config.practice_trials > 0 && practice_conditions_.empty())
    throw_input_error(
        config.source + "practice_trials",
        "no condition's images change with λ, so practice would show nothing to find");
  check_condition_procedures(study, config, conditions_);
  if (const auto problem =
          procedure_memory_problem(study, config, procedures::procedure_memory_limit()))
    throw_input_error(config.source + "procedure", *problem + " here");
  for (int c : conditions_) grids_.push_back(grid_of(study, c));
  for (size_t i = 0; i < conditions_.size(); ++i) {
    const auto& c = study.conditions[size_t(conditions_[i])];
    try {
      procedures_.push_back(std::make_unique<ConditionProcedure>(
          config.procedure_of(c.scene, c.method, c.sigma), config.max_trials, grids_[i],
          hash_combine(seed, uint64_t(conditions_[i])),
          config.procedure_source_of(c.scene, c.method, c.sigma)));
    } catch (const InputError& e) {  // which condition's grid it is
      throw InputError(std::string(e.what()) + " (condition " + c.scene + " / " + c.method +
                       " / σ " + format_value(c.sigma) + ")");
    }
  }
}

const std::optional<ChoiceTrial>& ChoiceRun::current() const {
  if (!planned_) current_ = plan_next(), planned_ = true;
  return current_;
}

bool ChoiceRun::ready() const {
  if (planned_ || in_practice()) return true;
  const auto slot = next_slot();
  return !slot || procedures_[*slot]->ready();
}

int ChoiceRun::slot_of(int condition) const {
  return int(std::find(conditions_.begin(), conditions_.end(), condition) - conditions_.begin());
}

// Practice trials show the largest λ of a practice condition: the easiest case of the task.
ChoiceTrial ChoiceRun::practice_trial(int k) const {
  SampleStream random(seed_, kStreamPractice, uint64_t(k), 0);
  ChoiceTrial t;
  t.practice = true;
  t.condition =
      practice_conditions_[std::min(size_t(random.next() * double(practice_conditions_.size())),
                                    practice_conditions_.size() - 1)];
  const ChoiceGrid grid = grid_of(study_, t.condition);
  t.intensity = {grid.lambdas.back(), grid.lambdas.size() - 1};
  t.lambda_index = grid.indices.back();
  t.lambda = grid.lambdas.back();
  t.target = std::min(int(random.next() * config_.n_afc), config_.n_afc - 1);
  return t;
}

std::optional<size_t> ChoiceRun::next_slot() const {
  std::vector<size_t> open;
  for (size_t i = 0; i < procedures_.size(); ++i)
    if (!procedures_[i]->finished()) open.push_back(i);
  if (open.empty()) return std::nullopt;
  SampleStream random(seed_, kStreamCondition, uint64_t(real_done_), 0);
  return open[std::min(size_t(random.next() * double(open.size())), open.size() - 1)];
}

std::optional<ChoiceTrial> ChoiceRun::plan_next() const {
  if (in_practice()) return practice_trial(practice_done_);
  const auto next = next_slot();
  if (!next) return std::nullopt;
  const size_t slot = *next;
  ChoiceTrial t;
  t.number = real_done_ + 1;
  t.condition = conditions_[slot];
  t.condition_trial = procedures_[slot]->trials() + 1;
  t.intensity = procedures_[slot]->next();
  t.lambda_index = grids_[slot].indices[t.intensity.grid];
  t.lambda = grids_[slot].lambdas[t.intensity.grid];
  t.target = balanced_target(seed_, t.condition, t.condition_trial - 1, config_.n_afc);
  return t;
}

bool ChoiceRun::answer(int response) {
  const ChoiceTrial t = *current();
  const bool correct = response == t.target;
  if (t.practice) {
    ++practice_done_;
  } else {
    procedures_[size_t(slot_of(t.condition))]->record(t.intensity, correct);
    ++real_done_;
  }
  planned_ = false;
  return correct;
}

nlohmann::ordered_json ChoiceRun::procedure_state(int condition) const {
  return procedures_[size_t(slot_of(condition))]->state();
}

}  // namespace countershade::forced_choice
