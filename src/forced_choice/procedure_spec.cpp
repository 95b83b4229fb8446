#include "forced_choice/procedure_spec.h"

#include <cmath>
#include <limits>
#include <optional>

#include "core/error.h"

namespace countershade::forced_choice {
namespace {

constexpr double kHuge = std::numeric_limits<double>::max();
constexpr int kMostTrials = 100000;

// minVal / maxVal: absent and null both mean no bound, as in StairHandler.
std::optional<double> optional_bound(const JsonObject& o, const std::string& key) {
  if (!o.has(key) || o.raw(key).is_null()) return std::nullopt;
  return o.number(key);
}

std::vector<double> step_sizes(const JsonObject& o) {
  if (!o.has("stepSizes")) return {4.0};
  std::vector<double> steps = o.raw("stepSizes").is_number()
                                  ? std::vector<double>{o.number("stepSizes")}
                                  : o.numbers("stepSizes");
  if (steps.empty()) o.fail("stepSizes", "must list at least one step size");
  for (double s : steps)
    if (!(s > 0)) o.fail("stepSizes", "step sizes must be above 0");
  return steps;
}

StaircaseRules read_staircase(const JsonObject& o) {
  StaircaseRules r;
  r.start = o.number("startVal");
  r.step_sizes = step_sizes(o);
  const std::string type = o.choice("stepType", "db", {"lin", "log", "db"});
  r.step_type = type == "lin" ? StepType::lin : type == "log" ? StepType::log : StepType::db;
  r.n_up = int(o.integer_in("nUp", 1, 1, 1000));
  r.n_down = int(o.integer_in("nDown", 3, 1, 1000));
  r.n_trials = int(o.integer_in("nTrials", 0, 0, kMostTrials));
  if (o.has("nReversals") && !o.raw("nReversals").is_null())
    r.n_reversals = int(o.integer_in("nReversals", 0, 0, kMostTrials));
  r.min_value = optional_bound(o, "minVal");
  r.max_value = optional_bound(o, "maxVal");
  r.apply_initial_rule = o.boolean_or("applyInitialRule", true);
  if (r.min_value && r.max_value && !(*r.min_value < *r.max_value))
    o.fail("maxVal", "must be above minVal");
  if ((r.min_value && r.start < *r.min_value) || (r.max_value && r.start > *r.max_value))
    o.fail("startVal", "must lie within [minVal, maxVal]");
  if (r.step_type != StepType::lin) {
    if (!(r.start > 0))
      o.fail("startVal", "must be above 0 for " + type + " steps (they multiply)");
    if (r.min_value && !(*r.min_value > 0))
      o.fail("minVal", "must be above 0 for " + type + " steps (they multiply)");
  }
  return r;
}

QuestParameters read_quest(const JsonObject& o) {
  QuestParameters q;
  q.t_guess = o.number("tGuess");
  q.t_guess_sd = o.number_in("tGuessSd", 0, 1e-9, kHuge);
  q.beta = o.number_in("beta", 0, 1e-9, 1e6);
  q.delta = o.number_in("delta", 0, 0, 0.999);
  q.gamma = o.number_in("gamma", 0, 0, 0.999);
  q.p_threshold = o.number("pThreshold");
  const double top = 1 - q.delta * (1 - q.gamma);  // the function's ceiling
  if (!(q.p_threshold > q.gamma && q.p_threshold < top))
    o.fail("pThreshold", "must lie strictly between gamma (" + std::to_string(q.gamma) +
                             ") and 1 − delta·(1 − gamma) (" + std::to_string(top) + ")");
  q.grain = o.number_in("grain", 0.01, 1e-9, kHuge);
  if (o.has("range") && !o.raw("range").is_null()) q.range = o.number_in("range", 0, 1e-9, kHuge);
  const double steps = q.range ? *q.range / q.grain : 500;
  if (steps > 1e6)
    o.fail(q.range ? "range" : "grain", "range / grain gives more than 1000000 grid points");
  return q;
}

}  // namespace

ProcedureSpec read_procedure(const JsonObject& block) {
  ProcedureSpec spec;
  block.string("type");  // required: an absent type is named as such
  const std::string type = block.choice("type", "", {"staircase", "quest"});
  if (type == "staircase") {
    spec.type = ProcedureType::staircase;
    spec.staircase = read_staircase(block);
    spec.n_trials = spec.staircase.n_trials;
  } else {
    spec.type = ProcedureType::quest;
    spec.quest = read_quest(block);
    spec.n_trials = int(block.integer_in("nTrials", 0, 0, kMostTrials));
  }
  return spec;
}

ProcedureSpec read_procedure_file(const std::filesystem::path& path) {
  const nlohmann::json root = parse_json_file(path);
  if (!root.is_object()) throw_input_error(path.string(), "expected a JSON object");
  JsonObject block(root, path.string(), "");
  ProcedureSpec spec = read_procedure(block);
  block.finish();
  if (spec.type == ProcedureType::quest)
    Quest check(spec.quest, path.string());  // a usable function
  return spec;
}

}  // namespace countershade::forced_choice
