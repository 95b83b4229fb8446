// `countershade serve` runs countershade-serve, the program beside this one that hosts a study
// (cli/serve_command.cpp): its HTTP, TLS and database libraries cost every other command 8 ms of
// start-up when linked here (docs/performance.md, "Start-up").

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "cli/command_line.h"
#include "cli/commands.h"

namespace countershade::cli {

void add_serve_dispatch(CLI::App& app) {
  app.add_subcommand("serve", kServeDescription)->allow_extras()->prefix_command();
}

int run_serve_program(char** argv) {
  std::error_code ec;
  const auto helper =
      std::filesystem::read_symlink("/proc/self/exe", ec).parent_path() / "countershade-serve";
  ::execv(helper.c_str(), argv);  // returns only when it could not
  print_error("failure: ", helper.string() + ": cannot run it (" + std::strerror(errno) +
                               "); build it with scripts/build");
  return 1;
}

}  // namespace countershade::cli
