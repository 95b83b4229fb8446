#include "analysis/method_comparison.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "analysis/stats.h"
#include "core/number_format.h"
#include "formats/responses.h"

namespace countershade::analysis {
namespace {

using json = nlohmann::ordered_json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Each included subject's mean λ_Low in one scene × σ of a block.
std::map<std::string, double> lambda_low_by_subject(const BlockResults& b, const std::string& scene,
                                                    double sigma) {
  std::map<std::string, double> out;
  const auto s = std::find(b.scenes.begin(), b.scenes.end(), scene);
  const auto g = std::find_if(b.sigmas.begin(), b.sigmas.end(),
                              [&](double x) { return std::abs(x - sigma) < 1e-12; });
  if (s == b.scenes.end() || g == b.sigmas.end()) return out;
  for (size_t i = 0; i < b.subjects.size(); ++i)
    out[b.subjects[i]] = b.lambda_means.at(i, size_t(s - b.scenes.begin()),
                                           size_t(g - b.sigmas.begin()), Question::low);
  return out;
}

void paired_test(MethodComparison& c) {
  std::vector<double> logs_low, logs_threshold, differences;
  for (size_t i = 0; i < c.subjects.size(); ++i) {
    logs_low.push_back(std::log(c.lambda_low[i]));
    logs_threshold.push_back(std::log(c.threshold[i]));
    differences.push_back(logs_low.back() - logs_threshold.back());
  }
  c.t = c.df = c.p = kNaN;
  if (c.subjects.empty()) return;
  c.geometric_mean_low = std::exp(summarize(logs_low).mean);
  c.geometric_mean_threshold = std::exp(summarize(logs_threshold).mean);
  c.mean_log_ratio = summarize(differences).mean;
  if (c.subjects.size() < 2) return;
  const TTest test = t_test(differences, 0);
  c.t = test.t, c.df = test.df, c.p = test.p;
}

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

}  // namespace

std::vector<MethodComparison> compare_methods(const std::vector<BlockResults>& adjustment,
                                              const ForcedChoiceResults& fc) {
  std::vector<MethodComparison> out;
  for (const PsychometricRow& pooled : fc.rows) {
    if (!pooled.pooled) continue;
    for (const BlockResults& b : adjustment) {
      if (!b.method.empty() && !pooled.label.empty() && b.method != pooled.label) continue;
      const auto low = lambda_low_by_subject(b, pooled.scene, pooled.sigma);
      MethodComparison c;
      c.scene = pooled.scene;
      c.method = pooled.label.empty() ? b.method : pooled.label;
      c.sigma = pooled.sigma;
      for (const PsychometricRow& row : fc.rows) {
        if (row.pooled || row.scene != pooled.scene || row.label != pooled.label ||
            row.sigma != pooled.sigma)
          continue;
        const auto it = low.find(row.subject);
        // A threshold needs a finite maximum of the likelihood, not a well-pinned slope: QUEST
        // places its trials near the threshold, where the slope is the least constrained.
        if (it == low.end() || !(it->second > 0)) continue;
        if (!row.fit.converged || !std::isfinite(row.fit.threshold)) {
          c.without_threshold.push_back(row.subject);
          continue;
        }
        c.subjects.push_back(row.subject);
        c.lambda_low.push_back(it->second);
        c.threshold.push_back(row.fit.threshold);
      }
      if (low.empty()) continue;
      paired_test(c);
      out.push_back(std::move(c));
    }
  }
  return out;
}

json comparison_json(const std::vector<MethodComparison>& rows) {
  json out = json::array();
  for (const MethodComparison& c : rows)
    out.push_back({{"scene", c.scene},
                   {"method", c.method},
                   {"sigma", c.sigma},
                   {"n_subjects", c.subjects.size()},
                   {"subjects_without_threshold", c.without_threshold},
                   {"geometric_mean_lambda_low", number_or_null(c.geometric_mean_low)},
                   {"geometric_mean_threshold", number_or_null(c.geometric_mean_threshold)},
                   {"mean_log_ratio", number_or_null(c.mean_log_ratio)},
                   {"t", number_or_null(c.t)},
                   {"df", number_or_null(c.df)},
                   {"p", number_or_null(c.p)}});
  return out;
}

std::string comparison_csv(const std::vector<MethodComparison>& rows) {
  std::string csv = csv_line({"scene", "method", "sigma", "subject", "lambda_low", "threshold"});
  for (const MethodComparison& c : rows)
    for (size_t i = 0; i < c.subjects.size(); ++i)
      csv += csv_line({c.scene, c.method, format_value(c.sigma), c.subjects[i],
                       format_value(round_to(c.lambda_low[i], 10)),
                       format_value(round_to(c.threshold[i], 10))});
  return csv;
}

}  // namespace countershade::analysis
