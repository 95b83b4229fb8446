#include "cli/command_line.h"

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "core/error.h"
#include "core/one_line.h"

namespace countershade::cli {

void print_error(const char* kind, const std::string& message, const char* suffix) {
  std::fprintf(stderr, "countershade: %s%s%s\n", kind, one_line(message).c_str(), suffix);
}

int run_command_line(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::RequiredError& e) {
    // CLI11 checks what is missing before what is unknown: a misspelt option would otherwise be
    // reported as the required option it did not set.
    const std::vector<std::string> unknown = app.remaining(true);
    std::string message = e.what();
    if (!unknown.empty()) {
      message = unknown.size() > 1 ? "The following arguments were not expected:"
                                   : "The following argument was not expected:";
      for (const std::string& argument : unknown) message += " " + argument;
    }
    print_error("error: ", message, " (see --help)");
    return 2;
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    print_error("error: ", e.what(), " (see --help)");
    return 2;
  } catch (const CommandFailed& e) {
    print_error("", e.what());
    return e.status;
  } catch (const InputError& e) {
    print_error("error: ", e.what());
    return 2;
  } catch (const std::exception& e) {
    print_error("failure: ", e.what());
    return 1;
  }
  return 0;
}

}  // namespace countershade::cli
