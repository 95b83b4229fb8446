// The parametric bootstrap of a psychometric fit (Wichmann & Hill 2001): data sets drawn from the
// fitted function with each cell's λ and n, refitted with the same model, for the threshold's
// percentile CI and the deviance's goodness-of-fit p-value.

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "analysis/psychometric_fit.h"
#include "analysis/psychometric_solver.h"
#include "core/random.h"

namespace countershade::analysis {
namespace {

// A binomial draw from one uniform number by walking the cumulative distribution from 0 (or, for
// p above 1/2, from n): exact, and the same on every platform, unlike std::binomial_distribution.
long long draw_binomial(long long n, double p, SampleStream& random) {
  if (p > 0.5) return n - draw_binomial(n, 1 - p, random);
  if (p <= 0) return 0;
  double term = std::pow(1 - p, double(n));
  if (!(term > 1e-280)) {  // too many trials for the walk: count Bernoulli draws
    long long k = 0;
    for (long long i = 0; i < n; ++i) k += random.next() < p;
    return k;
  }
  const double u = random.next(), ratio = p / (1 - p);
  double cumulative = term;
  long long k = 0;
  while (u >= cumulative && k < n) {
    term *= double(n - k) / double(k + 1) * ratio;
    cumulative += term;
    ++k;
  }
  return k;
}

// R's type-7 quantile of sorted values.
double quantile(const std::vector<double>& sorted, double p) {
  const double h = (double(sorted.size()) - 1) * p;
  const size_t i = size_t(std::floor(h));
  return i + 1 < sorted.size() ? sorted[i] + (h - double(i)) * (sorted[i + 1] - sorted[i])
                               : sorted[i];
}

struct Refit {
  double threshold = std::nan(""), deviance = std::nan("");
};

Refit refit_once(const PsychometricFit& fit, const CellData& data, SampleStream& random) {
  std::vector<BinomialCell> drawn = data.cells;
  for (BinomialCell& c : drawn)
    c.k = draw_binomial(c.n, psychometric_probability(fit, c.lambda), random);
  const CellData sample(std::move(drawn));
  const CoefficientStart from{fit.intercept, fit.slope};
  const LapseSolution s = fit.options.free_lapse
                              ? solve_free_lapse(sample, fit.options, from)
                              : solve_fixed_lapse(sample, fit.options, from, 0.0, 1e-9);
  Refit r;
  r.deviance = s.deviance;
  if (s.converged && std::isfinite(s.slope) && s.slope != 0) {
    r.threshold = std::exp((inverse_base(fit.options.model, 0.5) - s.intercept) / s.slope);
  }
  return r;
}

}  // namespace

void bootstrap_psychometric(PsychometricFit& fit, const std::vector<BinomialCell>& cells,
                            int resamples, uint64_t seed) {
  if (resamples <= 0 || !fit.converged || !std::isfinite(fit.threshold)) return;
  const CellData data(merge_cells(cells));
  std::vector<Refit> refits(static_cast<size_t>(resamples));
  tbb::parallel_for(0, resamples, [&](int b) {
    SampleStream random(seed, 6, uint64_t(b),
                        0);  // one stream per resample: independent of scheduling
    refits[size_t(b)] = refit_once(fit, data, random);
  });
  std::vector<double> thresholds;
  int at_least_as_bad = 0;
  for (const Refit& r : refits) {
    if (!std::isnan(r.threshold)) thresholds.push_back(r.threshold);
    at_least_as_bad += !(r.deviance < fit.deviance);  // a refit that failed counts against the fit
  }
  fit.p_deviance = (1.0 + at_least_as_bad) / (1.0 + resamples);
  fit.bootstrap = int(thresholds.size());
  if (thresholds.size() < 2) return;
  std::sort(thresholds.begin(), thresholds.end());
  fit.ci_low = quantile(thresholds, 0.025);
  fit.ci_high = quantile(thresholds, 0.975);
}

}  // namespace countershade::analysis
