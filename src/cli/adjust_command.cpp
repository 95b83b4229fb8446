// `countershade adjust`: runs a method-of-adjustment session over a stimulus set
// (docs/adjustment-study.md).

#include <memory>

#include "adjust/session.h"
#include "cli/commands.h"
#include "cli/display_flags.h"

namespace countershade::cli {

namespace {

// What runs a session without a person: a key script, screenshots, a model observer, the frame
// clock.
void add_automation_options(CLI::App* cmd, adjust::SessionOptions& o, std::string& script,
                            std::string& screenshot, std::string& observer) {
  cmd->add_option("--script", script, "Timed key events instead of a person (tests, demos)");
  cmd->add_option("--screenshot", screenshot,
                  "PNG written at each 'screenshot' line of the script");
  cmd->add_option("--observer", observer,
                  "A model observer answers: simulated:SEED (thresholds at shares of the grid), "
                  "or model:SEED[:PPD] (near the image-computable observer's 1, 2 and 4 JND)");
  cmd->add_flag(
      "--frame-clock", o.frame_clock,
      "With --script or --observer: time advances exactly one refresh period per frame and frames "
      "are "
      "not paced, so a scripted run does the same whatever the machine's load (tests, recordings)");
}

}  // namespace

void add_adjust_command(CLI::App& app) {
  auto o = std::make_shared<adjust::SessionOptions>();
  auto manifest = std::make_shared<std::string>();
  auto sessions = std::make_shared<std::string>("sessions");
  auto config = std::make_shared<std::string>();
  auto script = std::make_shared<std::string>();
  auto screenshot = std::make_shared<std::string>();
  auto observer = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "adjust", "Run an adjustment session (λ_Low, λ_High, λ_Best) over a stimulus set.");
  cmd->add_option("manifest", *manifest, "The stimulus set's manifest.json")->required();
  cmd->add_option("--subject", o->subject, "Participant id (letters, digits, '-', '_')")
      ->required();
  cmd->add_option("--session", o->session, "Session number (file SUBJECT_sNN.csv)")
      ->capture_default_str();
  cmd->add_option("--sessions", *sessions, "Folder for the session files")->capture_default_str();
  cmd->add_option("--procedure", *config,
                  "Procedure configuration JSON (default: the experiment's \"adjust\" object, else "
                  "built-in defaults)");
  cmd->add_flag("--resume", o->resume,
                "Continue an interrupted or quit session at its first unanswered question");
  cmd->add_flag("--fullscreen", o->fullscreen, "Fullscreen on the chosen monitor");
  cmd->add_option("--monitor", o->monitor, "Monitor number, from 0")->capture_default_str();
  cmd->add_option("--monitor-width-mm", o->monitor_width_mm,
                  "The monitor's visible width in mm, where it misreports its size (a set with a "
                  "screen is shown only "
                  "if the monitor's pixels per degree match the set's within 2 %)")
      ->check(CLI::Range(1.0, 1e5));
  add_output_path_flags(cmd, o->output_path, o->dither_seed);
  add_automation_options(cmd, *o, *script, *screenshot, *observer);
  cmd->callback([=] {
    adjust::SessionOptions run = *o;
    run.manifest = *manifest;
    run.sessions_dir = *sessions;
    if (!config->empty()) run.config = *config;
    if (!script->empty()) run.script = *script;
    if (!screenshot->empty()) run.screenshot = *screenshot;
    if (!observer->empty()) run.observer = *observer;
    adjust::run_session(run);
  });
  cmd->footer(
      "Keys: Up/Right stronger, Down/Left weaker, Enter confirm, Backspace previous question, Esc "
      "pause (then Q quits).\n"
      "Example:\n"
      "  countershade stimuli experiments/cornsweet/experiment.json -o stimuli/cornsweet\n"
      "  countershade adjust stimuli/cornsweet/manifest.json --subject P01\n"
      "  countershade analyze sessions/*_s01.csv -o reports/cornsweet");
}

}  // namespace countershade::cli
