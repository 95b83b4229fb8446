// Every floating-point option of every command refuses NaN and infinity: CLI11's range checks
// compare, and a NaN passes every comparison.

#include <cmath>
#include <cstdio>
#include <string>

#include "cli/commands.h"

namespace countershade::cli {

namespace {

// A number's check with a short message (CLI11's own name the largest double, 309 digits).
CLI::Validator sign_check(bool zero_allowed) {
  return CLI::Validator(
      [zero_allowed](std::string& text) -> std::string {
        double value = 0;
        try {
          value = std::stod(text);
        } catch (const std::exception&) {
          return "'" + text + "' is not a number";
        }
        if (zero_allowed ? value >= 0 : value > 0) return "";
        return std::string("must be ") + (zero_allowed ? "0 or more" : "more than 0") + ", not " +
               text;
      },
      zero_allowed ? "NONNEGATIVE" : "POSITIVE");
}

}  // namespace

const CLI::Validator kPositive = sign_check(false), kNonNegative = sign_check(true);

CLI::Validator within(double lowest, double highest) {
  char range[64];
  std::snprintf(range, sizeof range, "%g to %g", lowest, highest);
  return CLI::Validator(
      [lowest, highest, range = std::string(range)](std::string& text) -> std::string {
        double value = 0;
        try {
          value = std::stod(text);
        } catch (const std::exception&) {
          return "'" + text + "' is not a number";
        }
        return value >= lowest && value <= highest ? "" : "must be " + range + ", not " + text;
      },
      "FLOAT in " + std::string(range));
}

void reject_non_finite_numbers(CLI::App& app) {
  const CLI::Validator finite(
      [](std::string& text) -> std::string {
        double value = 0;
        try {
          value = std::stod(text);
        } catch (const std::exception&) {
          return "'" + text + "' is not a number a double can hold";
        }
        return std::isfinite(value) ? "" : "must be a finite number, not '" + text + "'";
      },
      "");
  for (CLI::App* command : app.get_subcommands({}))
    for (CLI::Option* option : command->get_options())
      if (option->get_type_name().rfind("FLOAT", 0) == 0)
        option->transform(finite);  // first: before range checks
}

}  // namespace countershade::cli
