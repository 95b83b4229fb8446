// `countershade choose`: runs a forced-choice session over a stimulus set (docs/forced-choice.md).

#include <memory>

#include "cli/commands.h"
#include "core/error.h"
#include "forced_choice/choice_session.h"

namespace countershade::cli {

void add_choose_command(CLI::App& app) {
  auto o = std::make_shared<forced_choice::ChoiceSessionOptions>();
  auto manifest = std::make_shared<std::string>();
  auto sessions = std::make_shared<std::string>("sessions");
  auto config = std::make_shared<std::string>();
  auto script = std::make_shared<std::string>();
  auto screenshot = std::make_shared<std::string>();
  auto observer = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "choose", "Run a forced-choice session (2AFC; constant stimuli, staircases or QUEST) over a stimulus set.");
  cmd->add_option("manifest", *manifest, "The stimulus set's manifest.json")->required();
  cmd->add_option("--subject", o->subject, "Participant id (letters, digits, '-', '_')")->required();
  cmd->add_option("--session", o->session, "Session number (file SUBJECT_sNN.forced-choice.csv)")->capture_default_str();
  cmd->add_option("--sessions", *sessions, "Folder for the session files")->capture_default_str();
  cmd->add_option("--procedure", *config, "Forced-choice configuration JSON (default: the experiment's \"forced_choice\" object)");
  cmd->add_flag("--resume", o->resume, "Continue an interrupted or quit session at its first unanswered trial");
  cmd->add_flag("--fullscreen", o->fullscreen, "Fullscreen on the chosen monitor");
  cmd->add_option("--monitor", o->monitor, "Monitor number, from 0")->capture_default_str();
  cmd->add_option("--script", *script, "Timed key events instead of a person (tests, demos)");
  cmd->add_option("--screenshot", *screenshot, "PNG written at each 'screenshot' line of the script");
  cmd->add_option("--observer", *observer, "A simulated observer answers from a Weibull: weibull:ALPHA,BETA,SEED");
  cmd->add_flag("--frame-clock", o->frame_clock,
                "With --script or --observer: time advances one refresh period per frame and frames are not paced");
  cmd->callback([=] {
    forced_choice::ChoiceSessionOptions run = *o;
    run.manifest = *manifest;
    run.sessions_dir = *sessions;
    if (!config->empty()) run.config = *config;
    if (!script->empty()) run.script = *script;
    if (!screenshot->empty()) run.screenshot = *screenshot;
    if (!observer->empty()) run.observer = *observer;
    if (run.frame_clock && !run.script && !run.observer)
      throw InputError("--frame-clock: needs --script or --observer (a person needs the real clock)");
    forced_choice::run_choice_session(run);
  });
  cmd->footer(
      "Keys: Left/Right choose the first (left) or second (right) image or interval, Esc pause (then Q quits).\n"
      "Example:\n"
      "  countershade choose stimuli/cornsweet/manifest.json --subject P01 --procedure quest.json\n"
      "  countershade analyze sessions/P01_s01.forced-choice.csv -o reports/cornsweet-2afc");
}

}  // namespace countershade::cli
