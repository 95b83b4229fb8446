#pragma once
// Reading the responses CSV (formats/responses.h) into typed answers. Unknown columns are
// ignored; every error names the file, the line and the column.

#include <filesystem>
#include <string>
#include <vector>

#include "formats/responses.h"

namespace countershade::analysis {

struct Response {
  std::string subject, scene, method;  // method is "" when the column is absent
  double sigma = 0, lambda = 0;
  Question question = Question::low;
  double lambda_step = 0;  // 0 when the column is absent
  std::string source;      // "file:line", for messages
};

std::vector<Response> read_responses(const std::filesystem::path& path);
std::vector<Response> read_responses(const std::vector<std::filesystem::path>& paths);

}  // namespace countershade::analysis
