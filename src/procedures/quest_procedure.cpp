// QUEST as a procedure: it works in log10 λ (quest.h); its recommendation is shown at the grid's
// nearest λ, and it is updated with the log10 of the λ shown.

#include <cmath>

#include "core/error.h"
#include "core/number_format.h"
#include "formats/responses.h"
#include "procedures/procedure.h"
#include "procedures/quest.h"

namespace countershade::procedures {
namespace {

using json = nlohmann::ordered_json;
constexpr int kMostTrials = 100000;
constexpr int kDefaultTrials = 40;  // per condition in a study, when nTrials is not given

class QuestProcedure final : public Procedure {
 public:
  QuestProcedure(const QuestParameters& parameters, int trials, const Grid& grid,
                 const std::string& where)
      : quest_(parameters, where), trials_(trials), grid_(grid) {}
  Intensity next() const override {
    const double requested = std::pow(10.0, quest_.quantile());
    return {requested, grid_.nearest(requested)};
  }
  void record(const Intensity& shown, bool correct) override {
    quest_.update(std::log10(grid_.lambdas[shown.grid]), correct);
  }
  bool finished() const override { return quest_.trials() >= trials_; }
  json state() const override {
    return {{"quest_mean", quest_.mean()},
            {"quest_sd", quest_.sd()},
            {"quest_quantile", quest_.quantile()}};
  }
  const Quest& quest() const { return quest_; }

 private:
  Quest quest_;
  int trials_;
  const Grid& grid_;
};

// The posterior must reach the set's grid, or QUEST would ask for λ the set cannot show.
void check_reaches_grid(const Quest& quest, const Grid& grid, const std::string& where) {
  const double lo = std::log10(grid.lambdas.front()), hi = std::log10(grid.lambdas.back());
  if (quest.highest() >= lo && quest.lowest() <= hi) return;
  throw_input_error(where + ".range",
                    "QUEST's thresholds (log10 λ " + format_value(round_to(quest.lowest(), 3)) +
                        " to " + format_value(round_to(quest.highest(), 3)) +
                        ") exclude the set's λ grid (log10 λ " + format_value(round_to(lo, 3)) +
                        " to " + format_value(round_to(hi, 3)) + ")");
}

class QuestSettings final : public ProcedureSettings {
 public:
  QuestSettings(QuestParameters parameters, int n_trials)
      : parameters_(parameters), n_trials_(n_trials) {}

  std::unique_ptr<Procedure> start(const Grid& grid, uint64_t,
                                   const std::string& where) const override {
    auto procedure = std::make_unique<QuestProcedure>(parameters_, trials(), grid, where);
    check_reaches_grid(procedure->quest(), grid, where);
    return procedure;
  }
  void describe(json& record) const override { record["trials"] = trials(); }
  Replay replay(const std::vector<bool>& responses, const std::string&) const override;

 private:
  int trials() const { return n_trials_ > 0 ? n_trials_ : kDefaultTrials; }
  QuestParameters parameters_;
  int n_trials_;  // 0: every answer (replay), kDefaultTrials (a study)
};

Replay QuestSettings::replay(const std::vector<bool>& responses, const std::string&) const {
  Replay out;
  out.csv = csv_line(
      {"trial", "intensity", "response", "quest_mean", "quest_mode", "quest_sd", "quest_quantile"});
  Quest quest(parameters_);
  size_t used = 0;
  while ((n_trials_ == 0 || int(used) < n_trials_) && used < responses.size()) {
    const double shown = quest.quantile();
    const bool correct = responses[used++];
    quest.update(shown, correct);
    out.csv += csv_line({std::to_string(used), exact_number(shown), correct ? "1" : "0",
                         exact_number(quest.mean()), exact_number(quest.mode()),
                         exact_number(quest.sd()), exact_number(quest.quantile())});
  }
  out.summary = {{"type", "quest"},
                 {"trials", used},
                 {"quest_mean", quest.mean()},
                 {"quest_mode", quest.mode()},
                 {"quest_sd", quest.sd()},
                 {"next_intensity", quest.quantile()},
                 {"quantile_order", quest.quantile_order()},
                 {"responses_left", responses.size() - used}};
  return out;
}

class QuestType final : public ProcedureType {
 public:
  std::string name() const override { return "quest"; }
  std::string summary() const override {
    return "QUEST (Watson & Pelli 1983) as Psychtoolbox computes it, in log10 λ";
  }
  std::vector<ParameterDoc> parameter_docs() const override {
    std::vector<ParameterDoc> docs = quest_parameter_docs();
    docs.push_back({"nTrials", "0",
                    "Trials per condition (0: 40 in a study, every answer in a "
                    "replay)"});
    return docs;
  }
  std::shared_ptr<const ProcedureSettings> parse(const ParameterBag& bag) const override {
    const QuestParameters parameters = read_quest_parameters(bag);
    const int n_trials = int(bag.integer_in("nTrials", 0, 0, kMostTrials));
    bag.finish(name());
    Quest check(parameters, bag.location());  // a usable psychometric function
    return std::make_shared<QuestSettings>(parameters, n_trials);
  }
};

}  // namespace

std::unique_ptr<const ProcedureType> make_quest_procedure() {
  return std::make_unique<QuestType>();
}

}  // namespace countershade::procedures
