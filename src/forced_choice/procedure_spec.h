#pragma once
// A forced-choice procedure as a file or an experiment's `procedure` block
// (docs/forced-choice.md): {"type": "staircase", …} with StairHandler's names, or
// {"type": "quest", …} with QuestCreate's. Every bad value is an InputError naming the key path.

#include <filesystem>
#include <string>

#include "core/json_reader.h"
#include "forced_choice/quest.h"
#include "forced_choice/staircase.h"

namespace countershade::forced_choice {

enum class ProcedureType { staircase, quest };

struct ProcedureSpec {
  ProcedureType type = ProcedureType::staircase;
  StaircaseRules staircase;  // when type is staircase
  QuestParameters quest;     // when type is quest
  int n_trials = 0;  // QUEST: trials per run, 0 = as many as there are answers (the staircase's own
                     // nTrials otherwise)
};

ProcedureSpec read_procedure(const JsonObject& block);
ProcedureSpec read_procedure_file(const std::filesystem::path& path);

}  // namespace countershade::forced_choice
