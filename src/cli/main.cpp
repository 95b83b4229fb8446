// countershade: stimuli, adjustment studies and analysis for contrast-enhancement research.
// Exit status: 0 success, 2 bad input or usage (one line on stderr), 1 any other failure.

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>

#include "cli/command_line.h"
#include "cli/commands.h"
#include "core/allocator.h"
#include "core/error.h"
#include "core/one_line.h"
#include "core/version.h"

namespace {

void add_commands(CLI::App& app) {
  using namespace countershade::cli;
  add_render_command(app);
  add_mesh_usm_command(app);
  add_image_usm_command(app);
  add_analyze_command(app);
  add_simulate_command(app);
  add_stimuli_command(app);
  add_adjust_command(app);
  add_choose_command(app);
  add_export_web_command(app);
  add_methods_command(app);
  add_procedures_command(app);
  add_audit_command(app);
  add_congruence_command(app);
  add_observe_command(app);
  add_predict_command(app);
  add_serve_dispatch(app);
  add_image_filter_command(app);
  add_flicker_command(app);
  add_sheet_command(app);
  add_calibrate_command(app);
  reject_non_finite_numbers(app);
}

using countershade::cli::print_error;

// CLI11 reports a mistyped command as "a subcommand is required"; this names it instead. False
// when `name` is not a command (the line is printed).
bool known_command(const CLI::App& app, const char* name) {
  std::string names;
  for (const CLI::App* sub : app.get_subcommands({})) {
    if (sub->get_name() == name) return true;
    names += (names.empty() ? "" : ", ") + sub->get_name();
  }
  print_error("error: ", "unknown command '" + std::string(name) + "' (commands: " + names + ")");
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  countershade::keep_freed_buffers_for_reuse();
  CLI::App app{
      "countershade: renders contrast-enhanced stimuli, runs adjustment studies and "
      "analyses them."};
  app.set_version_flag("--version", countershade::kVersion);
  app.require_subcommand(1);
  add_commands(app);
  if (argc > 1 && argv[1][0] != '-' && !known_command(app, argv[1])) return 2;
  if (argc > 1 && std::string(argv[1]) == "serve")
    return countershade::cli::run_serve_program(argv);
  return countershade::cli::run_command_line(app, argc, argv);
}
