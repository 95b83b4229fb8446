#pragma once
// Replaying a procedure on a given answer sequence, with no stimuli and no grid: how a lab checks
// what a staircase or QUEST will do before running it (`countershade simulate --procedure`), and
// how the procedures are checked against PsychoPy's and Psychtoolbox's sequences.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "forced_choice/procedure_spec.h"

namespace countershade::forced_choice {

struct Replay {
  std::string csv;  // one row per trial (docs/forced-choice.md, "Replaying a procedure")
  nlohmann::ordered_json summary;  // trials run, the final estimate, responses left over
};

// Runs the procedure until it finishes or the answers run out.
Replay replay_procedure(const ProcedureSpec& spec, const std::vector<bool>& responses);

// The `response` column (0 or 1, one row per trial) of a CSV; anything else is an InputError
// naming the file, line and column.
std::vector<bool> read_binary_responses(const std::filesystem::path& path);

// The shortest text that reads back as exactly `v`.
std::string exact_number(double v);

}  // namespace countershade::forced_choice
