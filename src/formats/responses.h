#pragma once
// The responses CSV (docs/data-formats): the three questions, the columns the adjustment app
// writes, and RFC 4180 reading and writing. The app writes it; the analysis reads it.

#include <optional>
#include <string>
#include <vector>

namespace countershade {

enum class Question { low = 0, high = 1, best = 2 };
inline constexpr int kQuestionCount = 3;
inline constexpr const char* kQuestionNames[] = {"low", "high", "best"};
inline const char* question_name(Question q) { return kQuestionNames[int(q)]; }
std::optional<Question> question_from_name(const std::string& name);

// The largest |λ| (and λ step) of a stimulus grid, and so of a recorded answer. Every method
// saturates long before; the bound keeps the grid's decimal rounding exact and the analysis's
// squares finite.
inline constexpr double kLargestLambda = 1e6;
// The most values a λ grid may have (its index is an int; 100,000 steps is already absurd).
inline constexpr int kMostLambdaValues = 100000;
// Grid values are rounded to this (so 0.15 is 0.15): a λ above 0 and below it is on no grid, and
// as a λ_Low it would turn JND = λ / λ_Low into numbers whose squares overflow.
inline constexpr double kLambdaResolution = 1e-9;

// The columns the app writes, in order: the required ones, then every optional one.
const std::vector<std::string>& response_columns();
// The columns every responses file must have.
const std::vector<std::string>& required_response_columns();

// RFC 4180 text: UTF-8 (an optional BOM is skipped), LF or CRLF line ends, quoted fields with
// embedded commas, quotes or line breaks. `lines` holds the physical line where each row starts
// (1-based). Malformed quoting is an InputError naming the file, the line and the column.
struct CsvTable {
  std::vector<std::vector<std::string>> rows;
  std::vector<size_t> lines;
};
CsvTable parse_csv(const std::string& text, const std::string& file);

// One CSV field, quoted when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& value);
// A whole line, with its newline.
std::string csv_line(const std::vector<std::string>& fields);

}  // namespace countershade
