// `countershade choose`: runs a forced-choice session over a stimulus set (docs/forced-choice.md).

#include <memory>

#include "cli/commands.h"
#include "cli/display_flags.h"
#include "core/error.h"
#include "forced_choice/choice_session.h"

namespace countershade::cli {
namespace {

struct ChooseArgs {
  forced_choice::ChoiceSessionOptions options;
  std::string manifest, sessions = "sessions", config, script, screenshot, observer;
};

void run(const ChooseArgs& a) {
  forced_choice::ChoiceSessionOptions run = a.options;
  run.manifest = a.manifest;
  run.sessions_dir = a.sessions;
  if (!a.config.empty()) run.config = a.config;
  if (!a.script.empty()) run.script = a.script;
  if (!a.screenshot.empty()) run.screenshot = a.screenshot;
  if (!a.observer.empty()) run.observer = a.observer;
  if (run.frame_clock && !run.script && !run.observer)
    throw InputError("--frame-clock: needs --script or --observer (a person needs the real clock)");
  forced_choice::run_choice_session(run);
}

}  // namespace

void add_choose_command(CLI::App& app) {
  auto a = std::make_shared<ChooseArgs>();
  forced_choice::ChoiceSessionOptions* o = &a->options;
  CLI::App* cmd = app.add_subcommand("choose",
                                     "Run a forced-choice session (2 to 4 alternatives; constant "
                                     "stimuli, staircases, QUEST or QUEST+) over a set.");
  cmd->add_option("manifest", a->manifest, "The stimulus set's manifest.json")->required();
  cmd->add_option("--subject", o->subject, "Participant id (letters, digits, '-', '_')")
      ->required();
  cmd->add_option("--session", o->session, "Session number (file SUBJECT_sNN.forced-choice.csv)")
      ->capture_default_str();
  cmd->add_option("--sessions", a->sessions, "Folder for the session files")->capture_default_str();
  cmd->add_option(
      "--procedure", a->config,
      "Forced-choice configuration JSON (default: the experiment's \"forced_choice\" object)");
  cmd->add_flag("--resume", o->resume,
                "Continue an interrupted or quit session at its first unanswered trial");
  cmd->add_flag("--fullscreen", o->fullscreen, "Fullscreen on the chosen monitor");
  cmd->add_option("--monitor", o->monitor, "Monitor number, from 0")->capture_default_str();
  cmd->add_option("--script", a->script, "Timed key events instead of a person (tests, demos)");
  cmd->add_option("--screenshot", a->screenshot,
                  "PNG written at each 'screenshot' line of the script");
  cmd->add_option("--observer", a->observer,
                  "A simulated observer answers from a Weibull in λ, weibull:ALPHA,BETA,SEED, or "
                  "in the image-computable observer's JND, model:SEED[:PPD]");
  add_output_path_flags(cmd, o->output_path, o->dither_seed);
  cmd->add_flag("--frame-clock", o->frame_clock,
                "With --script or --observer: time advances one refresh period per frame and "
                "frames are not paced");
  cmd->callback([a] { run(*a); });
  cmd->footer(
      "Keys: 1 to n choose an image (from the left) or interval (from the first); with two, "
      "Left/Right too.\n"
      "Esc pauses (then Enter resumes, Q quits).\n"
      "Example:\n"
      "  countershade choose stimuli/cornsweet/manifest.json --subject P01 --procedure quest.json\n"
      "  countershade analyze sessions/P01_s01.forced-choice.csv -o reports/cornsweet-2afc");
}

}  // namespace countershade::cli
