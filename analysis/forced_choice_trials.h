#pragma once
// Forced-choice trials as `analyze` reads them (docs/data-formats.md, "Forced-choice trials"): the
// minimal table other tools export (subject, scene, sigma, lambda, correct, n_afc) or the app's
// forced-choice CSV, which has those columns and more. Aggregated into binomial cells per
// condition, pooled over subjects and per subject.

#include <filesystem>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "analysis/psychometric_fit.h"

namespace countershade::analysis {

struct ForcedChoiceTrial {
  std::string subject, scene, label;  // label: "" in the minimal table
  double sigma = 0, lambda = 0;
  bool correct = false;
  int n_afc = 2;
  bool browser = false;   // from a browser session (the file has web columns)
  std::string procedure;  // the procedure that chose its λ ("" where the file has no such column)
  int line = 0;           // its line in the file, to name it in messages
};

// Whether a CSV header names the forced-choice columns (`correct` and `n_afc`).
bool is_forced_choice_header(const std::vector<std::string>& header);
bool is_forced_choice_file(const std::filesystem::path& path);

// Every trial of the files; a bad field is an InputError "file:line: column: what".
std::vector<ForcedChoiceTrial> read_forced_choice_trials(
    const std::vector<std::filesystem::path>& files);

// A condition: scene, label, σ.
using ConditionKey = std::tuple<std::string, std::string, double>;

struct ConditionCells {
  int n_afc = 2;
  std::vector<BinomialCell> pooled;                             // summed over subjects
  std::map<std::string, std::vector<BinomialCell>> by_subject;  // subject → cells
};

// Cells sorted by λ, one per λ. A condition whose trials disagree on n_afc is an InputError.
std::map<ConditionKey, ConditionCells> aggregate_cells(
    const std::vector<ForcedChoiceTrial>& trials);

}  // namespace countershade::analysis
