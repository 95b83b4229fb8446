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
  int lambda_index = -1;   // the answer's index on its grid; -1 when the column is absent
  double lambda_max = 0;   // the top of the grid the observer could reach; 0 when absent
  std::string source;      // "file:line", for messages
  bool browser = false;    // from a web-exported study (the file has the browser's columns)
};

std::vector<Response> read_responses(const std::filesystem::path& path);
std::vector<Response> read_responses(const std::vector<std::filesystem::path>& paths);

}  // namespace countershade::analysis
