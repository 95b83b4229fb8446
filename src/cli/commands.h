#pragma once
// One registration function per subcommand; main.cpp calls them all.

#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>

namespace countershade::cli {

// Thrown by a command that did its work but must exit with another status (e.g. a strict audit
// whose checks failed); main prints the message as one line and exits with `status`.
class CommandFailed : public std::runtime_error {
 public:
  CommandFailed(const std::string& what, int status) : std::runtime_error(what), status(status) {}
  int status;
};

void add_render_command(CLI::App& app);
void add_mesh_usm_command(CLI::App& app);
void add_image_usm_command(CLI::App& app);
void add_analyze_command(CLI::App& app);
void add_simulate_command(CLI::App& app);
void add_stimuli_command(CLI::App& app);
void add_adjust_command(CLI::App& app);
void add_choose_command(CLI::App& app);
void add_export_web_command(CLI::App& app);
void add_methods_command(CLI::App& app);
void add_procedures_command(CLI::App& app);
void add_audit_command(CLI::App& app);
void add_congruence_command(CLI::App& app);
void add_image_filter_command(CLI::App& app);
void add_flicker_command(CLI::App& app);
void add_sheet_command(CLI::App& app);
void add_calibrate_command(CLI::App& app);
void add_observe_command(CLI::App& app);
void add_predict_command(CLI::App& app);
// `serve` is a program of its own (countershade-serve beside this one), so that its HTTP and
// database libraries load only when a study is served: the subcommand here only lists it, and
// run_serve_program runs that program with the same arguments.
inline constexpr const char* kServeDescription =
    "Host an exported study (export-web) and keep every answer in a SQLite database; make "
    "participant links (--links); export the sessions as CSV files (--export)";
void add_serve_dispatch(CLI::App& app);
int run_serve_program(char** argv);
// What countershade-serve's main adds to its app.
void add_serve_command(CLI::App& app);

// Sign checks with one short line of message (use these, not CLI::PositiveNumber).
extern const CLI::Validator kPositive, kNonNegative;
// lowest ≤ value ≤ highest, with a short message (CLI11's Range prints six decimals: 1e-9 as 0).
CLI::Validator within(double lowest, double highest);

// Adds a check to every floating-point option of every command: NaN and infinity are refused.
void reject_non_finite_numbers(CLI::App& app);

}  // namespace countershade::cli
