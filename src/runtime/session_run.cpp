#include "runtime/session_run.h"

#include <algorithm>

#include "core/error.h"

namespace countershade::runtime {

const char* run_end_name(RunEnd end) {
  switch (end) {
    case RunEnd::running:
      return "running";
    case RunEnd::completed:
      return "completed";
    case RunEnd::quit:
      return "quit";
    case RunEnd::closed:
      return "closed";
    case RunEnd::interrupted:
      return "interrupted";
    case RunEnd::terminated:
      return "terminated";
    case RunEnd::script_ended:
      return "script-ended";
    case RunEnd::already_complete:
      return "already-complete";
    case RunEnd::display_failed:
      return "display-failed";
    case RunEnd::error:
      return "error";
  }
  return "running";
}

nlohmann::ordered_json SessionRun::to_json() const {
  using Json = nlohmann::ordered_json;
  Json pause_list = Json::array(), loss_list = Json::array();
  for (const Pause& p : pauses) {
    pause_list.push_back({{"at_s", p.at_s}, {"seconds", p.seconds}});
    if (p.quit) pause_list.back()["quit"] = true;
  }
  for (const FocusLoss& f : focus_losses) loss_list.push_back({{"at_s", f.at_s}, {"utc", f.utc}});
  Json out = {{"started_utc", started_utc},
              {"end", end == RunEnd::error ? "error: " + error : std::string(run_end_name(end))},
              {"resumed", resumed},
              {"answers_before", answers_before},
              {"answers", answers},
              {"pauses", pause_list},
              {"focus_losses", loss_list}};
  if (!display.is_null()) out["display"] = display;
  if (preload) out["preload"] = {{"images", preload->images}, {"seconds", preload->seconds}};
  if (!frames.is_null()) out["frames"] = frames;
  if (system_key_repeats_ignored) out["system_key_repeats_ignored"] = *system_key_repeats_ignored;
  if (!ended_utc.empty()) out["ended_utc"] = ended_utc;
  return out;
}

bool is_run_list(const nlohmann::ordered_json& runs) {
  return runs.is_array() &&
         std::all_of(runs.begin(), runs.end(), [](const auto& run) { return run.is_object(); });
}

void mark_unended_runs_interrupted(nlohmann::ordered_json& runs) {
  for (auto& run : runs)
    if (run.value("end", std::string()) == run_end_name(RunEnd::running))
      run["end"] = run_end_name(RunEnd::interrupted);
}

AppendOnlyFile open_answers_to_resume(const std::filesystem::path& file, const std::string& header,
                                      const nlohmann::ordered_json& runs) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  const bool begun = !ec && size > 0;
  int recorded = 0;
  const auto count = [](const nlohmann::ordered_json& run, const char* key) {
    return run.is_object() && run.contains(key) && run[key].is_number_integer()
               ? run[key].get<int>()
               : 0;
  };
  for (const auto& r : runs)
    recorded = std::max(recorded, count(r, "answers_before") + count(r, "answers"));
  if (!begun && recorded > 0)
    throw_input_error(file.string(), "missing or empty, but the sidecar records " +
                                         std::to_string(recorded) +
                                         " answers in it (restore it from a backup)");
  return AppendOnlyFile::open_to_resume(file, header);
}

}  // namespace countershade::runtime
