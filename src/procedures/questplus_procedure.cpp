// QUEST+ as a procedure: the block is a questplus definition (docs/forced-choice.md, "QUEST+").
// In a study its stimulus domain is the set's λ grid (or the listed part of it) on the block's
// scale; replayed on answers alone, the block lists its stimuli.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <optional>

#include "core/error.h"
#include "core/json_reader.h"
#include "core/number_format.h"
#include "formats/responses.h"
#include "procedures/procedure.h"
#include "procedures/questplus.h"

namespace countershade::procedures {
namespace {

using json = nlohmann::ordered_json;
constexpr int kDefaultTrials = 40;  // per condition in a study, when trials is not given

struct QuestPlusBlock {
  QuestPlusDefinition definition;
  bool stimuli_given = false;
  bool estimate_mean = true;  // param_estimation_method: mean (else mode)
  std::array<std::string, 2> outcomes{"Correct", "Incorrect"};
  int trials = 0;  // 0: not given
};

double to_scale(StimulusScale scale, double lambda) {
  if (scale == StimulusScale::log10) return std::log10(lambda);
  if (scale == StimulusScale::decibel) return 20 * std::log10(lambda);
  return lambda;
}

double from_scale(StimulusScale scale, double x) {
  if (scale == StimulusScale::log10) return std::pow(10.0, x);
  if (scale == StimulusScale::decibel) return std::pow(10.0, x / 20);
  return x;
}

json named(const QuestPlusDefinition& d, const ParameterPoint& values) {
  json out;
  const auto names = parameter_names(d.shape);
  for (size_t k = 0; k < kQuestPlusParameters; ++k) out[names[k]] = values[k];
  return out;
}

// The posterior's summary: the sidecar's state of a condition and the replay's final line.
// `estimate_mean`: the block's param_estimation_method, whose estimate is also "estimate".
json summary(const QuestPlus& q, bool estimate_mean) {
  const QuestPlusDefinition& d = q.definition();
  json out = {{"mode", named(d, q.mode())},
              {"mean", named(d, q.mean())},
              {"posterior_entropy", q.entropy()},
              {"estimate", named(d, estimate_mean ? q.mean() : q.mode())},
              {"quantile_2.5", named(d, q.quantile(0.025))},
              {"quantile_97.5", named(d, q.quantile(0.975))}};
  if (q.impossible_answers()) out["impossible_answers"] = q.impossible_answers();
  return out;
}

// Why the tables would not fit, if they would not: checked before anything is allocated.
std::optional<std::string> memory_problem(const QuestPlusDefinition& d) {
  const double need = d.bytes(), allowed = procedure_memory_limit();
  if (need <= allowed) return std::nullopt;
  return "the grid has " + format_value(double(d.parameter_points())) + " points; with " +
         std::to_string(d.stimuli.size()) + " stimuli its tables would need " +
         format_value(round_to(need / (1 << 30), 2)) + " GiB, more than half the memory here (" +
         format_value(round_to(allowed / (1 << 30), 2)) + " GiB)";
}

// The λ at which the function is halfway from its guess rate to its top (F = 1/2), where the
// psychometric fits of `analyze` put their threshold: α·(ln 2)^(1/β) for the Weibull with
// α = 10^t (log10), 10^(t/20) (dB) or t (linear); the mean for the normal CDF.
double lambda_at_half(PsychometricShape shape, StimulusScale scale, const ParameterPoint& p) {
  if (shape == PsychometricShape::norm_cdf) return p[0];
  return from_scale(scale, p[0]) * std::pow(std::log(2.0), 1 / p[1]);
}

class QuestPlusProcedure final : public Procedure {
 public:
  QuestPlusProcedure(QuestPlusDefinition definition, std::vector<size_t> points, int trials,
                     bool estimate_mean, const Grid& grid)
      : quest_(std::move(definition)),
        points_(std::move(points)),
        trials_(trials),
        estimate_mean_(estimate_mean),
        grid_(grid) {
    choose_in_background();  // the first trial's stimulus, while the instructions show
  }
  ~QuestPlusProcedure() override { settle(); }
  Intensity next() const override {
    settle();
    if (!next_) next_ = quest_.next();
    return {grid_.lambdas[points_[*next_]], points_[*next_]};
  }
  bool ready() const override {
    return next_ || (choosing_.valid() &&
                     choosing_.wait_for(std::chrono::seconds(0)) == std::future_status::ready);
  }
  // Updates the posterior, then chooses the next stimulus on another thread while the
  // participant sees the feedback or the blank between trials.
  void record(const Intensity& shown, bool correct) override {
    settle();
    next_.reset();
    update(shown, correct);
    choose_in_background();
  }
  bool finished() const override { return quest_.trials() >= trials_; }
  json state() const override { return summary(quest_, estimate_mean_); }

 private:
  void update(const Intensity& shown, bool correct) {
    for (size_t s = 0; s < points_.size(); ++s)
      if (points_[s] == shown.grid) return quest_.update(s, correct);
    const StimulusScale scale = quest_.definition().scale;
    quest_.update_at(to_scale(scale, grid_.lambdas[shown.grid]), correct);
  }
  void choose_in_background() {
#ifdef __EMSCRIPTEN__
    next_ = quest_.next();  // the browser's WebAssembly build has no threads: choose now
#else
    choosing_ = std::async(std::launch::async, [this] { return quest_.next(); });
#endif
  }
  // Takes the background choice, if one is under way.
  void settle() const {
    if (choosing_.valid()) next_ = choosing_.get();
  }

  QuestPlus quest_;
  std::vector<size_t> points_;  // the grid point of each stimulus
  int trials_;
  bool estimate_mean_;
  const Grid& grid_;
  mutable std::optional<size_t> next_;    // chosen once per trial: it costs a pass over the tables
  mutable std::future<size_t> choosing_;  // the choice under way; it only reads quest_
};

class QuestPlusSettings final : public ProcedureSettings {
 public:
  explicit QuestPlusSettings(QuestPlusBlock block) : block_(std::move(block)) {}

  std::unique_ptr<Procedure> start(const Grid& grid, uint64_t,
                                   const std::string& where) const override;
  void describe(json& record) const override { record["trials"] = trials(); }
  Replay replay(const std::vector<bool>& responses, const std::string& where) const override;
  std::optional<json> estimate(const std::vector<std::pair<double, bool>>& trials) const override;
  std::vector<MemoryPart> memory(const Grid& grid) const override {
    const QuestPlusDefinition d = block_.stimuli_given ? block_.definition : on_grid(grid);
    return {{d.tables_key(), d.table_bytes()}, {"", d.posterior_bytes()}};
  }

 private:
  int trials() const { return block_.trials > 0 ? block_.trials : kDefaultTrials; }
  // The definition with the set's whole λ grid as its stimuli, where the block lists none.
  QuestPlusDefinition on_grid(const Grid& grid) const {
    QuestPlusDefinition d = block_.definition;
    d.stimuli.clear();
    for (double lambda : grid.lambdas) d.stimuli.push_back(to_scale(d.scale, lambda));
    return d;
  }
  QuestPlusBlock block_;
};

std::unique_ptr<Procedure> QuestPlusSettings::start(const Grid& grid, uint64_t,
                                                    const std::string& where) const {
  QuestPlusDefinition d = block_.stimuli_given ? block_.definition : on_grid(grid);
  std::vector<size_t> points;
  for (size_t i = 0; i < d.stimuli.size(); ++i)
    points.push_back(block_.stimuli_given ? grid.point_of(from_scale(d.scale, d.stimuli[i]),
                                                          where + ".stim_domain.intensity")
                                          : i);
  // Its memory was checked with the session's other procedures (ChoiceRun), before any started.
  return std::make_unique<QuestPlusProcedure>(std::move(d), std::move(points), trials(),
                                              block_.estimate_mean, grid);
}

Replay QuestPlusSettings::replay(const std::vector<bool>& responses,
                                 const std::string& where) const {
  if (!block_.stimuli_given)
    throw_input_error(where,
                      "stim_domain: a replay needs the stimuli listed (a study takes the "
                      "set's λ grid)");
  QuestPlus quest(block_.definition);
  Replay out;
  out.csv = csv_line({"trial", "intensity", "response", "posterior_entropy"});
  const size_t n =
      block_.trials > 0 ? std::min(responses.size(), size_t(block_.trials)) : responses.size();
  for (size_t t = 0; t < n; ++t) {
    const size_t s = quest.next();
    quest.update(s, responses[t]);
    out.csv += csv_line({std::to_string(t + 1), exact_number(block_.definition.stimuli[s]),
                         block_.outcomes[responses[t] ? 0 : 1], exact_number(quest.entropy())});
  }
  out.summary = summary(quest, block_.estimate_mean);
  out.summary["trials"] = n;
  out.summary["responses_left"] = responses.size() - n;
  return out;
}

std::optional<json> QuestPlusSettings::estimate(
    const std::vector<std::pair<double, bool>>& trials) const {
  QuestPlusDefinition d = block_.definition;
  d.stimuli.clear();  // the λ shown, on the scale: the posterior needs nothing else
  for (const auto& [lambda, correct] : trials) d.stimuli.push_back(to_scale(d.scale, lambda));
  std::sort(d.stimuli.begin(), d.stimuli.end());
  d.stimuli.erase(std::unique(d.stimuli.begin(), d.stimuli.end()), d.stimuli.end());
  if (const auto problem = memory_problem(d)) throw_input_error("param_domain", *problem);
  QuestPlus quest(d);
  for (const auto& [lambda, correct] : trials) {
    const double x = to_scale(d.scale, lambda);
    quest.update(
        size_t(std::lower_bound(d.stimuli.begin(), d.stimuli.end(), x) - d.stimuli.begin()),
        correct);
  }
  json out = summary(quest, block_.estimate_mean);
  const auto half = quest.distribution_of(
      [&](const ParameterPoint& p) { return lambda_at_half(d.shape, d.scale, p); });
  out["lambda_at_half"] = {
      {"mode", half[0]}, {"mean", half[1]}, {"quantile_2.5", half[2]}, {"quantile_97.5", half[3]}};
  return out;
}

// A grid: one number, or a list that increases strictly.
std::vector<double> read_grid(const JsonObject& o, const std::string& key) {
  if (!o.has(key)) o.fail(key, "missing (a number or a list of numbers)");
  if (o.raw(key).is_number()) return {o.number(key)};
  std::vector<double> values = o.numbers(key);
  if (values.empty()) o.fail(key, "is empty");
  for (size_t i = 1; i < values.size(); ++i)
    if (!(values[i] > values[i - 1])) o.fail(key, "must increase strictly");
  return values;
}

void check_parameter_values(const JsonObject& o, const QuestPlusDefinition& d) {
  const auto names = parameter_names(d.shape);
  for (double v : d.grids[1])
    if (!(v > 0)) o.fail(names[1], "must be above 0");
  if (d.shape == PsychometricShape::weibull && d.scale == StimulusScale::linear)
    for (double v : d.grids[0])
      if (!(v > 0)) o.fail(names[0], "must be above 0 on a linear scale");
  for (size_t k : {size_t(2), size_t(3)})
    for (double v : d.grids[k])
      if (v < 0 || v >= 1) o.fail(names[k], "must be in [0, 1)");
  if (d.grids[2].back() + d.grids[3].back() >= 1)
    o.fail(names[3], "lower_asymptote + lapse_rate must stay below 1 (largest: " +
                         format_value(d.grids[2].back()) + " + " + format_value(d.grids[3].back()) +
                         ")");
}

void read_parameter_domain(const JsonObject& o, QuestPlusDefinition& d) {
  const auto names = parameter_names(d.shape);
  for (size_t k = 0; k < kQuestPlusParameters; ++k) d.grids[k] = read_grid(o, names[k]);
  o.finish();
  check_parameter_values(o, d);
}

void read_prior(const JsonObject& o, QuestPlusDefinition& d) {
  const auto names = parameter_names(d.shape);
  for (size_t k = 0; k < kQuestPlusParameters; ++k) {
    if (!o.has(names[k])) continue;
    std::vector<double> w = o.numbers(names[k]);
    if (w.size() != d.grids[k].size())
      o.fail(names[k], "has " + std::to_string(w.size()) + " weights for " +
                           std::to_string(d.grids[k].size()) + " values of param_domain." +
                           names[k]);
    double sum = 0;
    for (double v : w) {
      if (v < 0) o.fail(names[k], "weights must not be negative");
      sum += v;
    }
    if (!(sum > 0)) o.fail(names[k], "weights must not all be 0");
    d.prior[k] = std::move(w);
  }
  o.finish();
}

std::array<std::string, 2> read_outcomes(const JsonObject& o) {
  const nlohmann::json& r = o.raw("response");
  if (!r.is_array() || r.size() != 2 || !r[0].is_string() || !r[1].is_string() || r[0] == r[1])
    o.fail("response", "expected two different labels, the correct answer's first");
  o.finish();
  return {r[0].get<std::string>(), r[1].get<std::string>()};
}

QuestPlusBlock read_block(const ParameterBag& bag) {
  QuestPlusBlock b;
  QuestPlusDefinition& d = b.definition;
  d.shape = bag.choice("func", "weibull", {"weibull", "norm_cdf"}) == "weibull"
                ? PsychometricShape::weibull
                : PsychometricShape::norm_cdf;
  const std::string scale = bag.choice("stim_scale", "log10", {"log10", "dB", "linear"});
  d.scale = scale == "log10" ? StimulusScale::log10
            : scale == "dB"  ? StimulusScale::decibel
                             : StimulusScale::linear;
  if (d.shape == PsychometricShape::norm_cdf && d.scale != StimulusScale::linear)
    bag.fail("stim_scale", "norm_cdf works on a linear scale");
  if (const auto s = bag.structured("stim_domain")) {
    const JsonObject o = s->object();
    d.stimuli = read_grid(o, "intensity");
    o.finish();
    b.stimuli_given = true;
  }
  const auto p = bag.structured("param_domain");
  if (!p) bag.fail("param_domain", "missing (the grid of each parameter)");
  read_parameter_domain(p->object(), d);
  if (const auto prior = bag.structured("prior")) read_prior(prior->object(), d);
  if (const auto o = bag.structured("outcome_domain")) b.outcomes = read_outcomes(o->object());
  bag.choice("stim_selection_method", "min_entropy", {"min_entropy"});
  b.estimate_mean = bag.choice("param_estimation_method", "mean", {"mean", "mode"}) == "mean";
  b.trials = int(bag.integer_in("trials", 0, 0, 100000));
  if (const auto problem = memory_problem(d)) bag.fail("param_domain", *problem);
  return b;
}

class QuestPlusType final : public ProcedureType {
 public:
  std::string name() const override { return "questplus"; }
  std::string summary() const override {
    return "QUEST+ (Watson 2017): a posterior over threshold, slope, guess and lapse rate; each "
           "trial shows the stimulus that minimises the expected entropy";
  }
  std::vector<ParameterDoc> parameter_docs() const override;
  std::shared_ptr<const ProcedureSettings> parse(const ParameterBag& bag) const override {
    QuestPlusBlock block = read_block(bag);
    bag.finish(name());
    return std::make_shared<QuestPlusSettings>(std::move(block));
  }
};

std::vector<ParameterDoc> QuestPlusType::parameter_docs() const {
  return {
      {"param_domain", "",
       "The grid of each parameter, a number or an increasing list: threshold, slope, "
       "lower_asymptote, lapse_rate (norm_cdf: mean, sd, lower_asymptote, lapse_rate), in the "
       "stimulus scale's units; required"},
      {"func", "weibull", "The psychometric function: weibull or norm_cdf"},
      {"stim_scale", "log10", "The stimulus scale: log10 (of λ), dB (20·log10 λ) or linear (λ)"},
      {"stim_domain", "",
       "{\"intensity\": [x, …]}, on the scale. In a study, λ on the set's grid; absent: the whole "
       "grid. Required to replay"},
      {"prior", "",
       "Weights per parameter, one per grid value: {\"threshold\": [w, …]}; absent: uniform"},
      {"outcome_domain", "",
       "{\"response\": [\"Correct\", \"Incorrect\"]}: the labels, the correct answer's first"},
      {"stim_selection_method", "min_entropy", "min_entropy, the least expected entropy"},
      {"param_estimation_method", "mean",
       "The estimate reported first: mean (marginal means) or mode (the joint mode)"},
      {"trials", "0", "Trials per condition; 0: 40 in a study, every answer in a replay"},
  };
}

}  // namespace

std::unique_ptr<const ProcedureType> make_questplus_procedure() {
  return std::make_unique<QuestPlusType>();
}

}  // namespace countershade::procedures
