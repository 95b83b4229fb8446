// countershade: stimuli, adjustment studies and analysis for contrast-enhancement research.
// Exit status: 0 success, 2 bad input or usage (one line on stderr), 1 any other failure.

#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "core/error.h"
#include "core/version.h"

int main(int argc, char** argv) {
  CLI::App app{"countershade: renders contrast-enhanced stimuli, runs adjustment studies and "
               "analyses them."};
  app.set_version_flag("--version", countershade::kVersion);
  app.require_subcommand(1);
  countershade::cli::add_render_command(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::fprintf(stderr, "countershade: error: %s (see --help)\n", e.what());
    return 2;
  } catch (const countershade::InputError& e) {
    std::fprintf(stderr, "countershade: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "countershade: failure: %s\n", e.what());
    return 1;
  }
  return 0;
}
