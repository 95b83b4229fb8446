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
    const std::string key = rows[r].subject + '\x1f' + field(r, "session") + '\x1f' + field(r, "trial") + '\x1f' +
                            kQuestionNames[int(rows[r].question)];
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

}  // namespace

std::vector<Response> read_responses(const std::filesystem::path& path) {
  const std::string file = path.string();
  CsvTable table = parse_csv(read_file_bytes(path), file);
  if (table.rows.empty()) throw_input_error(file, "file is empty (expected a header row and responses)");

  const auto& header = table.rows[0];
  std::map<std::string, size_t> column;
  for (size_t c = 0; c < header.size(); ++c) {
    std::string name = header[c];
    while (!name.empty() && (name.back() == ' ' || name.back() == '\t')) name.pop_back();
    while (!name.empty() && (name.front() == ' ' || name.front() == '\t')) name.erase(name.begin());
    if (column.count(name))
      throw_input_error(file + ": line 1, column " + std::to_string(c + 1), "duplicate column '" + name + "'");
    column[name] = c;
  }
  for (const std::string& required : required_response_columns())
    if (!column.count(required)) throw_input_error(file + ": line 1", "missing column '" + required + "'");
  if (table.rows.size() == 1) throw_input_error(file, "no responses after the header row");

  auto where = [&](size_t r, const std::string& name) {
    return file + ": line " + std::to_string(table.lines[r]) + ", column " + std::to_string(column.at(name) + 1) +
           " (" + name + ")";
  };
  auto number = [&](size_t r, const std::string& name) {
    const std::string& text = table.rows[r][column.at(name)];
    size_t used = 0;
    double v = 0;
    try {
      v = std::stod(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (text.empty() || used != text.size() || !std::isfinite(v))
      throw_input_error(where(r, name), "'" + text + "' is not a number");
    return v;
  };

  std::vector<Response> out;
  for (size_t r = 1; r < table.rows.size(); ++r) {
    const auto& row = table.rows[r];
    if (row.size() != header.size())
      throw_input_error(file + ": line " + std::to_string(table.lines[r]),
                        "expected " + std::to_string(header.size()) + " fields, found " + std::to_string(row.size()));
    Response resp;
    resp.source = file + ":" + std::to_string(table.lines[r]);
    resp.subject = row[column["subject"]];
    resp.scene = row[column["scene"]];
    if (resp.subject.empty()) throw_input_error(where(r, "subject"), "empty subject id");
    if (resp.scene.empty()) throw_input_error(where(r, "scene"), "empty scene name");
    resp.sigma = number(r, "sigma");
    resp.lambda = number(r, "lambda");
    if (resp.lambda < 0) throw_input_error(where(r, "lambda"), "λ must not be negative");
    const std::string& q = row[column["question"]];
    auto question = question_from_name(q);
    if (!question) throw_input_error(where(r, "question"), "unknown question '" + q + "' (expected low, high or best)");
    resp.question = *question;
    if (column.count("method")) resp.method = row[column["method"]];
    if (column.count("lambda_step")) {
      resp.lambda_step = number(r, "lambda_step");
      if (!(resp.lambda_step > 0)) throw_input_error(where(r, "lambda_step"), "must be positive");
    }
    out.push_back(std::move(resp));
  }
  return latest_revisions(std::move(out), table, column);
}

std::vector<Response> read_responses(const std::vector<std::filesystem::path>& paths) {
  std::vector<Response> all;
  for (const auto& p : paths) {
    auto part = read_responses(p);
    all.insert(all.end(), std::make_move_iterator(part.begin()), std::make_move_iterator(part.end()));
  }
  return all;
}

}  // namespace countershade::analysis
