#pragma once
// The study analysis (docs/data-formats, results.json): preparation (repetitions averaged,
// incomplete subjects excluded), JND scaling, descriptives, repeated-measures ANOVAs, Holm-
// corrected t-tests, Ward clusters of preferences and interval-censored threshold fits.

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "analysis/cluster.h"
#include "analysis/fit.h"
#include "analysis/responses.h"
#include "analysis/stats.h"

namespace countershade::analysis {

struct AnalysisOptions {
  std::string normalization = "subject";  // subject | group
  std::optional<double> lambda_step;      // overrides the CSV's lambda_step column
  int clusters = 2;
  FitModel model = FitModel::lognormal;
  int bootstrap = 0;  // resamples per fit (0 = none)
  uint64_t seed = 1;
};

struct Exclusion {
  std::string subject, reason;
};

// Everything computed for one method block, kept for tables, figures and the report.
struct BlockResults {
  std::string method;  // "" when the CSV has no method column
  double lambda_step = 0;
  std::vector<std::string> subjects, scenes, warnings;  // subjects: included, sorted
  std::vector<double> sigmas;
  std::vector<Exclusion> excluded;
  // JND per included subject, [subject][scene][sigma][question].
  std::vector<std::vector<std::vector<std::array<double, 3>>>> jnd;
  std::vector<AnovaRow> anova, anova_best_sigma;
  Dendrogram dendrogram;
  std::vector<int> cluster_labels;  // per included subject
  struct FitEntry {
    std::string scene;
    double sigma;
    Question question;
    Fit fit;
    std::vector<double> answers;
  };
  std::vector<FitEntry> fits;
  nlohmann::ordered_json json;  // results.json content for this block (keys in schema order)
};

// Analyses every method block of `responses` (one block when there is no method column).
std::vector<BlockResults> analyze(const std::vector<Response>& responses, const AnalysisOptions& options);

}  // namespace countershade::analysis
