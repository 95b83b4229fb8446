#include "analysis/forced_choice_analysis.h"

#include <tbb/parallel_for.h>

#include <boost/math/distributions/beta.hpp>
#include <cmath>

#include "core/number_format.h"
#include "core/random.h"
#include "core/svg_plot.h"
#include "formats/responses.h"

namespace countershade::analysis {
namespace {

using json = nlohmann::ordered_json;

std::vector<PsychometricRow> planned_rows(const std::vector<ForcedChoiceTrial>& trials,
                                          std::vector<int>& n_afc) {
  std::vector<PsychometricRow> rows;
  for (const auto& [key, cells] : aggregate_cells(trials)) {
    const auto& [scene, label, sigma] = key;
    rows.push_back({true, "", scene, label, sigma, cells.pooled, {}});
    n_afc.push_back(cells.n_afc);
    for (const auto& [subject, subject_cells] : cells.by_subject) {
      rows.push_back({false, subject, scene, label, sigma, subject_cells, {}});
      n_afc.push_back(cells.n_afc);
    }
  }
  return rows;
}

std::string row_key(const PsychometricRow& r) {
  return (r.pooled ? "pooled" : "subject:" + r.subject) + "|" + r.scene + "|" + r.label + "|" +
         format_value(r.sigma);
}

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// Clopper–Pearson 95 % interval of k/n.
std::pair<double, double> binomial_interval(long long k, long long n) {
  using boost::math::beta_distribution;
  using boost::math::quantile;
  const double lo =
      k == 0 ? 0.0 : quantile(beta_distribution<>(double(k), double(n - k + 1)), 0.025);
  const double hi =
      k == n ? 1.0 : quantile(beta_distribution<>(double(k + 1), double(n - k)), 0.975);
  return {lo, hi};
}

}  // namespace

ForcedChoiceResults analyze_forced_choice(const std::vector<ForcedChoiceTrial>& trials,
                                          const ForcedChoiceOptions& options) {
  ForcedChoiceResults results;
  results.options = options;
  results.trials = trials.size();
  for (const ForcedChoiceTrial& t : trials) results.browser_trials += t.browser;
  std::vector<int> n_afc;
  results.rows = planned_rows(trials, n_afc);
  tbb::parallel_for(size_t(0), results.rows.size(), [&](size_t i) {
    PsychometricRow& row = results.rows[i];
    row.fit = fit_psychometric(row.cells, {options.model, 1.0 / n_afc[i], options.free_lapse});
    bootstrap_psychometric(row.fit, row.cells, options.bootstrap,
                           hash_combine(options.seed, hash_string(row_key(row))));
  });
  for (const PsychometricRow& row : results.rows)
    if (!row.fit.well_defined)
      results.warnings.push_back("psychometric fit " + row_key(row) + " is not well defined (" +
                                 (row.fit.converged ? "the likelihood has no single finite maximum"
                                                    : "separated data: the slope runs off") +
                                 ")");
  return results;
}

json forced_choice_json(const ForcedChoiceResults& r) {
  json fits = json::array();
  for (const PsychometricRow& row : r.rows) {
    const PsychometricFit& f = row.fit;
    fits.push_back({{"scope", row.pooled ? "pooled" : "subject"},
                    {"subject", row.pooled ? json(nullptr) : json(row.subject)},
                    {"scene", row.scene},
                    {"label", row.label},
                    {"sigma", row.sigma},
                    {"threshold", number_or_null(f.threshold)},
                    {"threshold_se", number_or_null(f.threshold_se)},
                    {"ci_low", number_or_null(f.ci_low)},
                    {"ci_high", number_or_null(f.ci_high)},
                    {"slope", f.slope},
                    {"intercept", f.intercept},
                    {"guess", f.options.guess},
                    {"lapse_rate", f.lapse},
                    {"deviance", f.deviance},
                    {"df", f.df},
                    {"aic", f.aic},
                    {"p_deviance", number_or_null(f.p_deviance)},
                    {"n_trials", f.n_trials},
                    {"converged", f.converged},
                    {"well_defined", f.well_defined}});
  }
  return {{"model", threshold_model_name(r.options.model)},
          {"lapse", r.options.free_lapse ? "free" : "fixed"},
          {"bootstrap", r.options.bootstrap},
          {"seed", r.options.seed},
          {"trials", r.trials},
          {"browser_trials", r.browser_trials},
          {"fits", fits},
          {"warnings", r.warnings}};
}

std::string psychometric_fits_csv(const ForcedChoiceResults& r) {
  std::string csv = csv_line(
      {"scope", "subject",   "scene",        "label",   "sigma",      "model",     "lapse",
       "guess", "threshold", "threshold_se", "slope",   "lapse_rate", "deviance",  "df",
       "aic",   "n_trials",  "ci_low",       "ci_high", "p_deviance", "converged", "well_defined"});
  auto number = [](double v) {
    return std::isfinite(v) ? format_value(round_to(v, 10)) : std::string("NA");
  };
  for (const PsychometricRow& row : r.rows) {
    const PsychometricFit& f = row.fit;
    csv += csv_line({row.pooled ? "pooled" : "subject",
                     row.subject,
                     row.scene,
                     row.label,
                     format_value(row.sigma),
                     threshold_model_name(f.options.model),
                     f.options.free_lapse ? "free" : "fixed",
                     number(f.options.guess),
                     number(f.threshold),
                     number(f.threshold_se),
                     number(f.slope),
                     number(f.lapse),
                     number(f.deviance),
                     std::to_string(f.df),
                     number(f.aic),
                     std::to_string(f.n_trials),
                     number(f.ci_low),
                     number(f.ci_high),
                     number(f.p_deviance),
                     f.converged ? "true" : "false",
                     f.well_defined ? "true" : "false"});
  }
  return csv;
}

std::vector<std::pair<std::string, std::string>> psychometric_figures(
    const ForcedChoiceResults& r) {
  std::vector<std::pair<std::string, std::string>> out;  // rows come sorted by scene
  for (const PsychometricRow& row : r.rows)
    if (row.pooled && (out.empty() || out.back().first != row.scene))
      out.push_back({row.scene, ""});
  for (auto& [scene, svg] : out) {
    LinePlot plot;
    plot.title =
        "Proportion correct: " + scene + " (pooled; 95 % intervals where a λ has 5 trials or more)";
    plot.x_label = "λ";
    plot.y_label = "proportion correct";
    plot.width = 760;
    size_t k = 0;
    for (const PsychometricRow& row : r.rows) {
      if (!row.pooled || row.scene != scene) continue;
      const std::string& c = plot_color(k++);
      PlotSeries data{(row.label.empty() ? "" : row.label + " ") + "σ " + format_value(row.sigma),
                      {},
                      {},
                      c,
                      false,
                      true};
      for (const BinomialCell& cell : row.cells) {
        const auto [lo, hi] = binomial_interval(cell.k, cell.n);
        data.x.push_back(cell.lambda);
        data.y.push_back(double(cell.k) / double(cell.n));
        if (cell.n >= 5)
          plot.error_bars.push_back(
              {cell.lambda, lo, hi, c});  // fewer: an interval of nearly [0, 1]
      }
      PlotSeries curve{"", {}, {}, c};
      const double lo = row.cells.front().lambda, hi = row.cells.back().lambda;
      for (int i = 0; i <= 100; ++i) {
        const double lambda = lo + (hi - lo) * i / 100.0;
        curve.x.push_back(lambda);
        curve.y.push_back(psychometric_probability(row.fit, lambda));
      }
      plot.series.push_back(data);
      plot.series.push_back(curve);
    }
    plot.height = std::max(400, 110 + 18 * int(plot.series.size() / 2));
    svg = plot.to_svg();
  }
  return out;
}

}  // namespace countershade::analysis
