#include "analysis/forced_choice_trials.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/file_bytes.h"
#include "formats/responses.h"

namespace countershade::analysis {
namespace {

const std::vector<std::string> kRequired = {"subject", "scene",   "sigma",
                                            "lambda",  "correct", "n_afc"};

struct Columns {
  std::map<std::string, size_t> index;
  bool has(const std::string& name) const { return index.count(name) > 0; }
};

Columns header_columns(const std::vector<std::string>& header, const std::string& file) {
  Columns c;
  for (size_t i = 0; i < header.size(); ++i) c.index[header[i]] = i;
  for (const std::string& name : kRequired)
    if (!c.has(name))
      throw_input_error(
          file,
          "no '" + name +
              "' column (forced-choice trials need subject, scene, sigma, lambda, correct, n_afc)");
  return c;
}

double number_field(const std::string& text, const std::string& where, const std::string& column) {
  size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v))
    throw_input_error(where, column + ": expected a number, got '" + text + "'");
  return v;
}

ForcedChoiceTrial parse_trial(const std::vector<std::string>& row, const Columns& c,
                              const std::string& file, size_t line) {
  const std::string where = file + ":" + std::to_string(line);
  auto field = [&](const std::string& name) -> std::string {
    const size_t i = c.index.at(name);
    if (i >= row.size())
      throw_input_error(where,
                        name + ": missing (the row has " + std::to_string(row.size()) + " fields)");
    return row[i];
  };
  ForcedChoiceTrial t;
  t.subject = field("subject");
  t.scene = field("scene");
  if (t.subject.empty()) throw_input_error(where, "subject: empty");
  if (t.scene.empty()) throw_input_error(where, "scene: empty");
  if (c.has("label"))
    t.label = field("label");
  else if (c.has("method"))
    t.label = field("method");  // the app's forced-choice CSV
  t.sigma = number_field(field("sigma"), where, "sigma");
  t.lambda = number_field(field("lambda"), where, "lambda");
  if (!(t.lambda > 0))
    throw_input_error(where,
                      "lambda: must be above 0 (a forced-choice trial shows some enhancement)");
  const std::string correct = field("correct");
  if (correct != "0" && correct != "1")
    throw_input_error(where, "correct: expected 0 or 1, got '" + correct + "'");
  t.correct = correct == "1";
  const double n = number_field(field("n_afc"), where, "n_afc");
  if (n != std::floor(n) || n < 2 || n > 16)
    throw_input_error(where, "n_afc: expected a whole number of alternatives from 2 to 16");
  t.n_afc = int(n);
  t.browser = c.has("device_pixel_ratio");
  if (c.has("procedure")) t.procedure = field("procedure");
  t.line = int(line);
  return t;
}

// A browser's temporal trial whose intervals ran a frame long or short (docs/online-study.md):
// recorded, shown again, and not an answer to count.
bool shown_mistimed(const std::vector<std::string>& row, const Columns& c) {
  const auto it = c.index.find("interval_timing");
  return it != c.index.end() && it->second < row.size() && row[it->second] == "mistimed";
}

}  // namespace

bool is_forced_choice_header(const std::vector<std::string>& header) {
  return std::count(header.begin(), header.end(), "correct") &&
         std::count(header.begin(), header.end(), "n_afc");
}

bool is_forced_choice_file(const std::filesystem::path& path) {
  const CsvTable table = parse_csv(read_file_bytes(path), path.string());
  return !table.rows.empty() && is_forced_choice_header(table.rows.front());
}

std::vector<ForcedChoiceTrial> read_forced_choice_trials(
    const std::vector<std::filesystem::path>& files) {
  std::vector<ForcedChoiceTrial> trials;
  for (const auto& path : files) {
    const std::string file = path.string();
    const CsvTable table = parse_csv(read_file_bytes(path), file);
    if (table.rows.empty()) throw_input_error(file, "empty file");
    const Columns columns = header_columns(table.rows.front(), file);
    for (size_t r = 1; r < table.rows.size(); ++r)
      if (!shown_mistimed(table.rows[r], columns))
        trials.push_back(parse_trial(table.rows[r], columns, file, table.lines[r]));
    if (table.rows.size() < 2) throw_input_error(file, "no trials after the header");
  }
  return trials;
}

std::map<ConditionKey, ConditionCells> aggregate_cells(
    const std::vector<ForcedChoiceTrial>& trials) {
  std::map<ConditionKey, std::map<double, BinomialCell>> pooled;
  std::map<ConditionKey, std::map<std::string, std::map<double, BinomialCell>>> by_subject;
  std::map<ConditionKey, ConditionCells> out;
  for (const ForcedChoiceTrial& t : trials) {
    const ConditionKey key{t.scene, t.label, t.sigma};
    auto [it, fresh] = out.try_emplace(key);
    if (fresh)
      it->second.n_afc = t.n_afc;
    else if (it->second.n_afc != t.n_afc)
      throw InputError("forced-choice trials: condition " + t.scene + " σ " +
                       std::to_string(t.sigma) + " mixes " + std::to_string(it->second.n_afc) +
                       "- and " + std::to_string(t.n_afc) + "-alternative trials");
    for (BinomialCell* cell : {&pooled[key][t.lambda], &by_subject[key][t.subject][t.lambda]}) {
      cell->lambda = t.lambda;
      cell->k += t.correct;
      cell->n += 1;
    }
  }
  for (auto& [key, cells] : out) {
    for (const auto& [lambda, cell] : pooled[key]) cells.pooled.push_back(cell);
    for (const auto& [subject, by_lambda] : by_subject[key])
      for (const auto& [lambda, cell] : by_lambda) cells.by_subject[subject].push_back(cell);
  }
  return out;
}

}  // namespace countershade::analysis
