#pragma once
// The study analysis (docs/data-formats, results.json): preparation (repetitions averaged,
// incomplete subjects excluded), JND scaling, descriptives, repeated-measures ANOVAs, Holm-
// corrected t-tests, Ward clusters of preferences and interval-censored threshold fits.

#include <array>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "analysis/cluster.h"
#include "analysis/fit.h"
#include "analysis/responses.h"
#include "analysis/stats.h"

namespace countershade::analysis {

// Which λ_Low a subject's JND unit is: the subject's own, or the mean over subjects (per scene ×
// σ).
enum class JndNormalization { subject, group };
JndNormalization parse_jnd_normalization(const std::string& name);  // throws InputError
const char* jnd_normalization_name(JndNormalization normalization);

struct AnalysisOptions {
  JndNormalization normalization = JndNormalization::subject;
  std::optional<double> lambda_step;  // overrides the CSV's lambda_step column
  int clusters = 2;
  ThresholdModel model = ThresholdModel::log_normal;
  int bootstrap = 0;  // resamples per fit (0 = none)
  uint64_t seed = 1;
};

struct Exclusion {
  std::string subject, reason;
};

// One value per included subject × scene × σ × question, flat and in that order (row-major).
class CellTable {
 public:
  CellTable() = default;
  CellTable(size_t subjects, size_t scenes, size_t sigmas)
      : subjects_(subjects),
        scenes_(scenes),
        sigmas_(sigmas),
        values_(subjects * scenes * sigmas * kQuestionCount, 0.0) {}
  double& at(size_t subject, size_t scene, size_t sigma, Question q) {
    return values_[index(subject, scene, sigma, q)];
  }
  double at(size_t subject, size_t scene, size_t sigma, Question q) const {
    return values_[index(subject, scene, sigma, q)];
  }
  // A subject's mean over σ in one scene, and over scenes and σ.
  double sigma_mean(size_t subject, size_t scene, Question q) const;
  double subject_mean(size_t subject, Question q) const;
  size_t subjects() const { return subjects_; }
  size_t scenes() const { return scenes_; }
  size_t sigmas() const { return sigmas_; }

 private:
  size_t index(size_t subject, size_t scene, size_t sigma, Question q) const {
    return ((subject * scenes_ + scene) * sigmas_ + sigma) * kQuestionCount + size_t(q);
  }
  size_t subjects_ = 0, scenes_ = 0, sigmas_ = 0;
  std::vector<double> values_;
};

// Everything computed for one method block, kept for tables, figures and the report.
struct BlockResults {
  std::string method;  // "" when the CSV has no method column
  size_t browser_answers =
      0;  // from a web-exported study (for the report; results.json does not differ)
  double lambda_step = 0;
  std::vector<std::string> subjects, scenes, warnings;  // subjects: included, sorted
  std::vector<double> sigmas;
  std::vector<Exclusion> excluded;
  CellTable jnd;           // JND per included subject, scene, σ and question
  CellTable lambda_means;  // the same subjects' mean answers in λ (repetitions averaged)
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
std::vector<BlockResults> analyze(const std::vector<Response>& responses,
                                  const AnalysisOptions& options);

}  // namespace countershade::analysis
