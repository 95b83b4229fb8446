// countershade-serve: `countershade serve`, as a program of its own (cli/serve_dispatch.cpp runs
// it with the same arguments, "serve" included).

#include "cli/command_line.h"
#include "cli/commands.h"
#include "core/version.h"

int main(int argc, char** argv) {
  CLI::App app{"countershade: hosts an exported study"};
  app.set_version_flag("--version", countershade::kVersion);
  app.require_subcommand(1);
  countershade::cli::add_serve_command(app);
  countershade::cli::reject_non_finite_numbers(app);
  return countershade::cli::run_command_line(app, argc, argv);
}
