#pragma once
// Parsing and running a command line, with the exit statuses every countershade program shares:
// 0 success, 2 bad input or usage (one line on stderr), 1 any other failure.

#include <CLI/CLI.hpp>
#include <string>

namespace countershade::cli {

// One line on stderr, whatever the message quotes from the user's files.
void print_error(const char* kind, const std::string& message, const char* suffix = "");

// Parses argv into `app` and runs the command's callback; returns the exit status.
int run_command_line(CLI::App& app, int argc, char** argv);

}  // namespace countershade::cli
