#include "runtime/session_run.h"

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

}  // namespace countershade::runtime
