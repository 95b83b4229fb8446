#include "forced_choice/replay.h"

#include <charconv>
#include <cmath>

#include "core/error.h"
#include "core/file_bytes.h"
#include "formats/responses.h"

namespace countershade::forced_choice {
namespace {

using json = nlohmann::ordered_json;

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

Replay replay_staircase(const StaircaseRules& rules, const std::vector<bool>& responses) {
  Replay out;
  out.csv = csv_line({"trial", "intensity", "response", "reversal"});
  Staircase stair(rules);
  size_t used = 0;
  while (!stair.finished() && used < responses.size()) {
    const double shown = stair.next_intensity();
    const bool reversal = stair.add_response(responses[used++]);
    out.csv += csv_line({std::to_string(used), exact_number(shown), responses[used - 1] ? "1" : "0",
                         reversal ? "1" : "0"});
  }
  out.summary = {{"type", "staircase"},
                 {"trials", used},
                 {"finished", stair.finished()},
                 {"reversals", stair.reversal_intensities().size()},
                 {"final_estimate", number_or_null(stair.estimate())},
                 {"final_estimate_geometric", number_or_null(stair.geometric_estimate())},
                 {"next_intensity", stair.next_intensity()},
                 {"responses_left", responses.size() - used}};
  return out;
}

Replay replay_quest(const QuestParameters& parameters, int n_trials,
                    const std::vector<bool>& responses) {
  Replay out;
  out.csv = csv_line(
      {"trial", "intensity", "response", "quest_mean", "quest_mode", "quest_sd", "quest_quantile"});
  Quest quest(parameters);
  size_t used = 0;
  while ((n_trials == 0 || int(used) < n_trials) && used < responses.size()) {
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

}  // namespace

std::string exact_number(double v) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

Replay replay_procedure(const ProcedureSpec& spec, const std::vector<bool>& responses) {
  if (spec.type == ProcedureType::staircase) return replay_staircase(spec.staircase, responses);
  return replay_quest(spec.quest, spec.n_trials, responses);
}

std::vector<bool> read_binary_responses(const std::filesystem::path& path) {
  const std::string file = path.string();
  const CsvTable table = parse_csv(read_file_bytes(path), file);
  if (table.rows.empty())
    throw_input_error(file, "empty file (expected a header with a 'response' column)");
  const auto& header = table.rows.front();
  size_t column = header.size();
  for (size_t i = 0; i < header.size(); ++i)
    if (header[i] == "response") column = i;
  if (column == header.size()) throw_input_error(file, "no 'response' column in the header");
  std::vector<bool> responses;
  for (size_t r = 1; r < table.rows.size(); ++r) {
    const auto& row = table.rows[r];
    const std::string value = column < row.size() ? row[column] : "";
    if (value != "0" && value != "1")
      throw_input_error(file + ":" + std::to_string(table.lines[r]),
                        "response: expected 0 or 1, got '" + value + "'");
    responses.push_back(value == "1");
  }
  return responses;
}

}  // namespace countershade::forced_choice
