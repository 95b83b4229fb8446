#include "analysis/responses.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "core/error.h"
#include "core/file_bytes.h"

namespace countershade::analysis {

namespace {

// The adjustment app writes a new row, with a higher `revision`, when an observer goes back and
// answers a question again; only the latest answer to each question of a trial counts.
std::vector<Response> latest_revisions(std::vector<Response> rows, const CsvTable& table,
                                       const std::map<std::string, size_t>& column) {
  if (!column.count("revision") || !column.count("trial")) return rows;
  auto field = [&](size_t r, const char* name) -> std::string {
    auto it = column.find(name);
    return it == column.end() ? std::string() : table.rows[r + 1][it->second];
  };
  std::map<std::string, std::pair<long, size_t>> latest;  // question key → (revision, row)
  for (size_t r = 0; r < rows.size(); ++r) {
    const std::string key = rows[r].subject + '\x1f' + field(r, "session") + '\x1f' +
                            field(r, "trial") + '\x1f' + kQuestionNames[int(rows[r].question)];
    const std::string text = field(r, "revision");
    char* end = nullptr;
    const long revision = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || revision < 0)
      throw_input_error(rows[r].source + " (revision)", "'" + text + "' is not a revision number");
    auto [it, inserted] = latest.emplace(key, std::make_pair(revision, r));
    if (!inserted && revision >= it->second.first) it->second = {revision, r};
  }
  std::vector<bool> keep(rows.size(), false);
  for (const auto& [key, value] : latest) keep[value.second] = true;
  std::vector<Response> out;
  for (size_t r = 0; r < rows.size(); ++r)
    if (keep[r]) out.push_back(std::move(rows[r]));
  return out;
}

// Reads the rows of one responses CSV; every error names the file, the line and the column.
class ResponseRows {
 public:
  ResponseRows(CsvTable table, std::string file)
      : table_(std::move(table)), file_(std::move(file)) {
    if (table_.rows.empty())
      throw_input_error(file_, "file is empty (expected a header row and responses)");
    const auto& header = table_.rows[0];
    for (size_t c = 0; c < header.size(); ++c) {
      if (column_.count(header[c]))
        throw_input_error(file_ + ": line 1, column " + std::to_string(c + 1),
                          "duplicate column '" + header[c] + "'");
      column_[header[c]] = c;
    }
    for (const std::string& required : required_response_columns())
      if (!column_.count(required))
        throw_input_error(file_ + ": line 1", "missing column '" + required + "'");
    if (table_.rows.size() == 1) throw_input_error(file_, "no responses after the header row");
  }

  std::vector<Response> read() const {
    std::vector<Response> out;
    for (size_t r = 1; r < table_.rows.size(); ++r) out.push_back(row(r));
    return latest_revisions(std::move(out), table_, column_);
  }

 private:
  Response row(size_t r) const {
    if (table_.rows[r].size() != table_.rows[0].size())
      throw_input_error(file_ + ": line " + std::to_string(table_.lines[r]),
                        "expected " + std::to_string(table_.rows[0].size()) + " fields, found " +
                            std::to_string(table_.rows[r].size()));
    Response resp;
    resp.source = file_ + ":" + std::to_string(table_.lines[r]);
    resp.subject = text(r, "subject");
    resp.scene = text(r, "scene");
    if (resp.subject.empty()) throw_input_error(where(r, "subject"), "empty subject id");
    if (resp.scene.empty()) throw_input_error(where(r, "scene"), "empty scene name");
    resp.sigma = number(r, "sigma");
    resp.lambda = number(r, "lambda");
    if (resp.lambda < 0) throw_input_error(where(r, "lambda"), "λ must not be negative");
    if (resp.lambda > kLargestLambda)
      throw_input_error(where(r, "lambda"), "λ beyond 1e6, the largest of any stimulus grid");
    if (resp.lambda > 0 && resp.lambda < kLambdaResolution)
      throw_input_error(where(r, "lambda"), "λ between 0 and 1e-9 is on no stimulus grid");
    auto question = question_from_name(text(r, "question"));
    if (!question)
      throw_input_error(where(r, "question"), "unknown question '" + text(r, "question") +
                                                  "' (expected low, high or best)");
    resp.question = *question;
    if (column_.count("method")) resp.method = text(r, "method");
    resp.browser = column_.count("device_pixel_ratio") > 0;
    read_grid(r, resp);
    return resp;
  }

  // The optional grid columns: step, index and the top of the grid.
  void read_grid(size_t r, Response& resp) const {
    if (column_.count("lambda_step")) {
      resp.lambda_step = number(r, "lambda_step");
      if (!(resp.lambda_step > 0) || resp.lambda_step > kLargestLambda)
        throw_input_error(where(r, "lambda_step"), "must be positive and at most 1e6");
    }
    if (column_.count("lambda_index")) {
      const double index = number(r, "lambda_index");
      if (index < 0 || index != std::floor(index) || index > 1e9)
        throw_input_error(where(r, "lambda_index"),
                          "'" + text(r, "lambda_index") + "' is not a whole number ≥ 0");
      resp.lambda_index = int(index);
    }
    if (column_.count("lambda_max")) {
      resp.lambda_max = number(r, "lambda_max");
      if (!(resp.lambda_max > 0) || resp.lambda_max > kLargestLambda)
        throw_input_error(where(r, "lambda_max"), "must be positive and at most 1e6");
      if (resp.lambda > resp.lambda_max * (1 + 1e-9))
        throw_input_error(where(r, "lambda"), "λ " + text(r, "lambda") + " is above lambda_max " +
                                                  text(r, "lambda_max"));
    }
  }

  const std::string& text(size_t r, const std::string& name) const {
    return table_.rows[r][column_.at(name)];
  }
  std::string where(size_t r, const std::string& name) const {
    return file_ + ": line " + std::to_string(table_.lines[r]) + ", column " +
           std::to_string(column_.at(name) + 1) + " (" + name + ")";
  }
  double number(size_t r, const std::string& name) const {
    const std::string& t = text(r, name);
    size_t used = 0;
    double v = 0;
    try {
      v = std::stod(t, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (t.empty() || used != t.size() || !std::isfinite(v))
      throw_input_error(where(r, name), "'" + t + "' is not a number");
    return v;
  }

  CsvTable table_;
  std::string file_;
  std::map<std::string, size_t> column_;
};

}  // namespace

std::vector<Response> read_responses(const std::filesystem::path& path) {
  return ResponseRows(parse_csv(read_file_bytes(path), path.string()), path.string()).read();
}

std::vector<Response> read_responses(const std::vector<std::filesystem::path>& paths) {
  std::vector<Response> all;
  for (const auto& p : paths) {
    auto part = read_responses(p);
    all.insert(all.end(), std::make_move_iterator(part.begin()),
               std::make_move_iterator(part.end()));
  }
  return all;
}

}  // namespace countershade::analysis
