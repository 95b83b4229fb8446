#pragma once
// The responses CSV (docs/data-formats): RFC 4180, UTF-8 (an optional BOM is skipped), LF or CRLF
// line ends, quoted fields with embedded commas, quotes or line breaks. Unknown columns are
// ignored. Every error names the file, the line and the column.

#include <filesystem>
#include <string>
#include <vector>

namespace countershade::analysis {

enum class Question { low = 0, high = 1, best = 2 };
inline constexpr const char* kQuestionNames[] = {"low", "high", "best"};

struct Response {
  std::string subject, scene, method;  // method is "" when the column is absent
  double sigma = 0, lambda = 0;
  Question question = Question::low;
  double lambda_step = 0;  // 0 when the column is absent
  std::string source;      // "file:line", for messages
};

// Parses CSV text into rows of fields; `first_line` of each row is recorded for messages.
struct CsvTable {
  std::vector<std::vector<std::string>> rows;
  std::vector<size_t> lines;  // physical line where each row starts (1-based)
};
CsvTable parse_csv(const std::string& text, const std::string& file);

std::vector<Response> read_responses(const std::filesystem::path& path);
std::vector<Response> read_responses(const std::vector<std::filesystem::path>& paths);

// Writes one CSV field, quoted when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& value);

}  // namespace countershade::analysis
