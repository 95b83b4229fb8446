// countershade: stimuli, adjustment studies and analysis for contrast-enhancement research.
// Exit status: 0 success, 2 bad input or usage (one line on stderr), 1 any other failure.

#include <cstdio>
#include <exception>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/commands.h"
#include "core/allocator.h"
#include "core/error.h"
#include "core/version.h"

int main(int argc, char** argv) {
  countershade::keep_freed_buffers_for_reuse();
  CLI::App app{"countershade: renders contrast-enhanced stimuli, runs adjustment studies and "
               "analyses them."};
  app.set_version_flag("--version", countershade::kVersion);
  app.require_subcommand(1);
  countershade::cli::add_render_command(app);
  countershade::cli::add_mesh_usm_command(app);
  countershade::cli::add_image_usm_command(app);
  countershade::cli::add_analyze_command(app);
  countershade::cli::add_simulate_command(app);
  countershade::cli::add_stimuli_command(app);
  countershade::cli::add_adjust_command(app);
  countershade::cli::add_methods_command(app);
  countershade::cli::add_audit_command(app);
  countershade::cli::add_congruence_command(app);
  countershade::cli::add_image_filter_command(app);
  countershade::cli::add_flicker_command(app);
  countershade::cli::reject_non_finite_numbers(app);

  // CLI11 reports a mistyped command as "a subcommand is required"; name it instead.
  if (argc > 1 && argv[1][0] != '-') {
    bool known = false;
    std::string names;
    for (const CLI::App* sub : app.get_subcommands({})) {
      known |= sub->get_name() == argv[1];
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    if (!known) {
      std::fprintf(stderr, "countershade: error: unknown command '%s' (commands: %s)\n", argv[1], names.c_str());
      return 2;
    }
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::fprintf(stderr, "countershade: error: %s (see --help)\n", e.what());
    return 2;
  } catch (const countershade::cli::CommandFailed& e) {
    std::fprintf(stderr, "countershade: %s\n", e.what());
    return e.status;
  } catch (const countershade::InputError& e) {
    std::fprintf(stderr, "countershade: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "countershade: failure: %s\n", e.what());
    return 1;
  }
  return 0;
}
