#include "procedures/answer_file.h"

#include "core/error.h"
#include "core/file_bytes.h"
#include "formats/responses.h"

namespace countershade::procedures {
std::vector<bool> read_binary_responses(const std::filesystem::path& path) {
  const std::string file = path.string();
  const CsvTable table = parse_csv(read_file_bytes(path), file);
  if (table.rows.empty())
    throw_input_error(file, "empty file (expected a header with a 'response' column)");
  const auto& header = table.rows.front();
  size_t column = header.size();
  for (size_t i = 0; i < header.size(); ++i)
    if (header[i] == "response") column = i;
  if (column == header.size()) throw_input_error(file, "no 'response' column in the header");
  std::vector<bool> responses;
  for (size_t r = 1; r < table.rows.size(); ++r) {
    const auto& row = table.rows[r];
    const std::string value = column < row.size() ? row[column] : "";
    const bool correct = value == "1" || value == "Correct";
    if (!correct && value != "0" && value != "Incorrect")
      throw_input_error(file + ":" + std::to_string(table.lines[r]),
                        "response: expected 1 or Correct, 0 or Incorrect, got '" + value + "'");
    responses.push_back(correct);
  }
  return responses;
}

}  // namespace countershade::procedures
