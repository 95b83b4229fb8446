#include "analysis/procedure_estimates.h"

#include <cmath>
#include <map>
#include <tuple>

#include "core/error.h"
#include "core/json_reader.h"
#include "core/number_format.h"
#include "formats/responses.h"
#include "procedures/choice_block.h"
#include "procedures/registry.h"

namespace countershade::analysis {
namespace {

namespace fs = std::filesystem;
using Trials = std::vector<std::pair<double, bool>>;                    // λ shown, correct
using Key = std::tuple<std::string, std::string, std::string, double>;  // subject, scene, label, σ

// A condition's trials, and one row of each procedure its `procedure` column names.
struct ConditionTrials {
  Trials trials;
  std::map<std::string, int> procedures;  // name → the line of its first row
};

std::map<Key, ConditionTrials> trials_by_condition(const fs::path& file) {
  std::map<Key, ConditionTrials> out;
  for (const ForcedChoiceTrial& t : read_forced_choice_trials({file})) {
    ConditionTrials& c = out[{t.subject, t.scene, t.label, t.sigma}];
    c.trials.push_back({t.lambda, t.correct});
    if (!t.procedure.empty()) c.procedures.try_emplace(t.procedure, t.line);
  }
  return out;
}

// The record's procedure replays the trials only if they are the ones it chose: a row that names
// another (an edited record, or a session file beside another's record) would give its estimate
// to trials it never saw.
void require_same_procedure(const fs::path& file, const ConditionTrials& c,
                            const procedures::ProcedureBlock& block, const std::string& path) {
  for (const auto& [name, line] : c.procedures)
    if (name != block.type)
      throw InputError(file.string() + ":" + std::to_string(line) + ": procedure: the trial ran '" +
                       name + "', but " + path + " is '" + block.type + "'");
}

// The procedures a session's record (its sidecar's "config") names: the block's, and those of
// the conditions that ran another (docs/forced-choice.md, "Procedures per condition").
class SessionProcedures {
 public:
  SessionProcedures(const nlohmann::json& record, const std::string& file) : file_(file) {
    const JsonObject config = JsonObject(record, file, "").object("config");
    block_ = procedures::read_procedure_block(config.raw("procedure"), file, "config.procedure");
    own_ = procedures::read_condition_procedures(config, file);
  }
  // The procedure of a condition, and "FILE: KEY PATH" of where the record gives it.
  std::pair<const procedures::ProcedureBlock&, std::string> of(const std::string& scene,
                                                               const std::string& label,
                                                               double sigma) const {
    for (const auto& c : own_)
      if (c.condition.names(scene, label, sigma)) return {c.procedure, c.where};
    return {block_, file_ + ": config.procedure"};
  }

 private:
  std::string file_;
  procedures::ProcedureBlock block_;
  std::vector<procedures::ConditionProcedureBlock> own_;
};

// The estimates of one session file: one per condition whose procedure keeps a posterior.
std::vector<ProcedureEstimate> estimates_of(const fs::path& file) {
  fs::path sidecar = file;
  sidecar.replace_extension(".json");
  std::vector<ProcedureEstimate> out;
  if (!fs::exists(sidecar)) return out;
  const nlohmann::json record = parse_json_file(sidecar);
  const JsonObject root(record, sidecar.string(), "");
  const SessionProcedures procedures(record, sidecar.string());
  const int session = int(root.integer_or("session", 0));
  for (const auto& [key, condition] : trials_by_condition(file)) {
    const auto& [subject, scene, label, sigma] = key;
    const auto& [block, path] = procedures.of(scene, label, sigma);
    require_same_procedure(file, condition, block, path);
    const Trials& trials = condition.trials;
    std::optional<nlohmann::ordered_json> estimate;
    try {
      estimate = block.settings->estimate(trials);
    } catch (const InputError& e) {  // named by the block it comes from
      throw InputError(path + "." + e.what());
    }
    if (estimate)
      out.push_back({subject, session, scene, label, sigma, trials.size(), std::move(*estimate)});
  }
  return out;
}

std::string number(const nlohmann::ordered_json& v) {
  if (!v.is_number()) return "NA";
  const double x = v.get<double>();
  return std::isfinite(x) ? format_value(round_to(x, 10)) : std::string("NA");
}

const PsychometricRow* fit_of(const ForcedChoiceResults& fits, const ProcedureEstimate& e) {
  for (const auto& row : fits.rows)
    if (!row.pooled && row.subject == e.subject && row.scene == e.scene && row.label == e.label &&
        row.sigma == e.sigma)
      return &row;
  return nullptr;
}

}  // namespace

std::vector<ProcedureEstimate> procedure_estimates(const std::vector<fs::path>& files,
                                                   std::vector<std::string>& warnings) {
  std::vector<ProcedureEstimate> out;
  for (const fs::path& file : files) {
    try {
      for (auto& e : estimates_of(file)) out.push_back(std::move(e));
    } catch (const InputError& e) {
      warnings.push_back(std::string(e.what()) + "; its procedure's own estimates are left out");
    }
  }
  return out;
}

std::string procedure_estimates_csv(const std::vector<ProcedureEstimate>& estimates,
                                    const ForcedChoiceResults& fits) {
  std::string csv = csv_line({"subject", "session", "scene", "label", "sigma", "trials", "quantity",
                              "mode", "mean", "quantile_2.5", "quantile_97.5", "fit_threshold",
                              "fit_ci_low", "fit_ci_high"});
  for (const ProcedureEstimate& e : estimates) {
    const std::vector<std::string> condition = {
        e.subject, std::to_string(e.session), e.scene,
        e.label,   format_value(e.sigma),     std::to_string(e.trials)};
    auto row = [&](const std::string& quantity, const nlohmann::ordered_json& mode,
                   const nlohmann::ordered_json& mean, const nlohmann::ordered_json& low,
                   const nlohmann::ordered_json& high, const PsychometricRow* fit) {
      std::vector<std::string> fields = condition;
      for (const std::string& f : {quantity, number(mode), number(mean), number(low), number(high)})
        fields.push_back(f);
      for (double v : {fit ? fit->fit.threshold : NAN, fit ? fit->fit.ci_low : NAN,
                       fit ? fit->fit.ci_high : NAN})
        fields.push_back(std::isfinite(v) ? format_value(round_to(v, 10)) : "NA");
      csv += csv_line(fields);
    };
    const auto& s = e.estimate;
    for (const auto& [name, mode] : s["mode"].items())
      row(name, mode, s["mean"][name], s["quantile_2.5"][name], s["quantile_97.5"][name], nullptr);
    if (s.contains("lambda_at_half")) {
      const auto& h = s["lambda_at_half"];
      row("lambda_at_half", h["mode"], h["mean"], h["quantile_2.5"], h["quantile_97.5"],
          fit_of(fits, e));
    }
  }
  return csv;
}

nlohmann::ordered_json procedure_estimates_json(const std::vector<ProcedureEstimate>& estimates) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const ProcedureEstimate& e : estimates)
    out.push_back({{"subject", e.subject},
                   {"session", e.session},
                   {"scene", e.scene},
                   {"label", e.label},
                   {"sigma", e.sigma},
                   {"trials", e.trials},
                   {"estimate", e.estimate}});
  return out;
}

}  // namespace countershade::analysis
