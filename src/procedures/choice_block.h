#pragma once
// The forced-choice study's block of an experiment file, or a file of its own
// (docs/forced-choice.md): n = 2 to 4 alternatives, side by side (spatial) or one after the other
// (temporal), the question, optional feedback, and the procedure (registry.h) that picks each
// condition's λ. It is read here, apart from the app, so that an experiment is checked when its
// set is made; the app (src/forced_choice) runs it.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/json_reader.h"
#include "procedures/condition_selection.h"
#include "procedures/registry.h"

namespace countershade::procedures {

enum class Layout { spatial, temporal };
const char* layout_name(Layout layout);

// A procedure that one condition runs instead of the block's own, so that one session can mix
// constant stimuli with adaptive procedures (docs/forced-choice.md, "Procedures per condition").
struct ConditionProcedureBlock {
  ConditionSelection condition;
  ProcedureBlock procedure;
  nlohmann::ordered_json source;  // the entry, for the session's record
  std::string where;              // "FILE: KEY PATH" of its procedure, to name it in messages
};

struct ChoiceConfig {
  int n_afc = 2;
  Layout layout = Layout::spatial;
  int interval_frames = 30,
      blank_frames = 30;    // temporal layout: each interval, and the blank between
  int feedback_frames = 0;  // 0: no feedback
  std::string question = "Which image is enhanced?";
  // Empty: a text that fits the layout and the number of alternatives (welcome_text()).
  std::string welcome;
  ProcedureBlock procedure;  // the plug-in that picks each condition's λ
  std::vector<ConditionProcedureBlock> condition_procedures;  // conditions that run another
  int max_trials = 200;  // any procedure: a condition ends after this many trials
  std::vector<ConditionSelection> conditions;  // empty: every condition of the set
  std::vector<ConditionSelection>
      practice_conditions;  // empty: conditions whose images change with λ
  int practice_trials = 0;
  std::optional<uint64_t> seed;
  nlohmann::json procedure_source;  // the procedure block as written, for the session's record
  std::string source;               // "FILE: KEY PATH." of the block, to name it in messages

  // The procedure a condition runs: its own entry in condition_procedures, else the block's.
  const ProcedureBlock& procedure_of(const std::string& scene, const std::string& method,
                                     double sigma) const;
  // Where that procedure is written ("FILE: KEY PATH"), to name it in messages.
  std::string procedure_source_of(const std::string& scene, const std::string& method,
                                  double sigma) const;

  nlohmann::ordered_json to_json() const;
  std::string welcome_text() const;
  // The entry of condition_procedures that names this condition; none when it runs `procedure`.
  const ConditionProcedureBlock* own_procedure(const std::string& scene, const std::string& method,
                                               double sigma) const;
  // The keys that answer, for the hint under the images: "Left/Right" or "1 to 4".
  std::string answer_keys() const;
};

// The block's "condition_procedures" list (none when absent), for the block and for a session's
// record of it; a condition listed twice is an InputError.
std::vector<ConditionProcedureBlock> read_condition_procedures(const JsonObject& block,
                                                               const std::string& file);

// Reads the block; every bad value is an InputError naming `file` and the key path.
ChoiceConfig parse_choice_config(const nlohmann::json& value, const std::string& file,
                                 const std::string& path);

}  // namespace countershade::procedures
