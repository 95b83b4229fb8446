#include "procedures/questplus.h"

#ifndef __EMSCRIPTEN__
#include <tbb/parallel_for.h>
#endif

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numeric>

namespace countershade::procedures {
namespace {

// body(i) for every i < n: on the app's threads, and in order in the browser's WebAssembly build
// (which has none). Each i writes only its own results, so both give the same numbers.
template <class Body>
void for_each_index(size_t n, const Body& body) {
#ifdef __EMSCRIPTEN__
  for (size_t i = 0; i < n; ++i) body(i);
#else
  tbb::parallel_for(size_t(0), n, body);
#endif
}

// −q ln q, with 0 ln 0 = 0.
double information(double q) { return q > 0 ? -q * std::log(q) : 0.0; }

double binary_entropy(double p) { return information(p) + information(1 - p); }

// The index of each parameter at a flat point (the grid's C order: the last parameter fastest).
std::array<size_t, kQuestPlusParameters> unflatten(
    size_t point, const std::array<std::vector<double>, kQuestPlusParameters>& grids) {
  std::array<size_t, kQuestPlusParameters> index{};
  for (size_t k = kQuestPlusParameters; k-- > 0;) {
    index[k] = point % grids[k].size();
    point /= grids[k].size();
  }
  return index;
}

// The parameters' values at a flat point.
ParameterPoint values_at(size_t point,
                         const std::array<std::vector<double>, kQuestPlusParameters>& grids) {
  const auto index = unflatten(point, grids);
  ParameterPoint p{};
  for (size_t k = 0; k < kQuestPlusParameters; ++k) p[k] = grids[k][index[k]];
  return p;
}

// The outer product of the per-parameter weights, normalised.
std::vector<double> joint_prior(const QuestPlusDefinition& d, size_t points) {
  std::vector<double> prior(points, 1.0);
  for (size_t point = 0; point < points; ++point) {
    const auto index = unflatten(point, d.grids);
    for (size_t k = 0; k < kQuestPlusParameters; ++k)
      if (!d.prior[k].empty()) prior[point] *= d.prior[k][index[k]];
  }
  const double sum = std::accumulate(prior.begin(), prior.end(), 0.0);
  for (double& p : prior) p /= sum;
  return prior;
}

}  // namespace

std::array<std::string, kQuestPlusParameters> parameter_names(PsychometricShape shape) {
  if (shape == PsychometricShape::norm_cdf) return {"mean", "sd", "lower_asymptote", "lapse_rate"};
  return {"threshold", "slope", "lower_asymptote", "lapse_rate"};
}

double psychometric(PsychometricShape shape, StimulusScale scale, double x,
                    const ParameterPoint& p) {
  const double guess = p[2], lapse = p[3];
  if (shape == PsychometricShape::norm_cdf)
    return guess + (1 - guess - lapse) * 0.5 * std::erfc(-(x - p[0]) / p[1] / std::sqrt(2.0));
  double growth = 0;  // the Weibull's exponent on each scale
  switch (scale) {
    case StimulusScale::log10:
      growth = std::pow(10.0, p[1] * (x - p[0]));
      break;
    case StimulusScale::decibel:
      growth = std::pow(10.0, p[1] * (x - p[0]) / 20);
      break;
    case StimulusScale::linear:
      growth = std::pow(x / p[0], p[1]);
      break;
  }
  return 1 - lapse - (1 - guess - lapse) * std::exp(-growth);
}

size_t QuestPlusDefinition::parameter_points() const {
  size_t n = 1;
  for (const auto& g : grids) n *= g.size();
  return n;
}

double QuestPlusDefinition::posterior_bytes() const {
  double points = 1;
  for (const auto& g : grids) points *= double(g.size());
  return points * sizeof(double);
}

double QuestPlusDefinition::table_bytes() const {
  return 2 * double(stimuli.size()) * posterior_bytes();
}

std::string QuestPlusDefinition::tables_key() const {
  std::string key{char(shape), char(scale)};
  const auto add = [&key](const std::vector<double>& values) {
    const size_t n = values.size();
    key.append(reinterpret_cast<const char*>(&n), sizeof n);
    key.append(reinterpret_cast<const char*>(values.data()), n * sizeof(double));
  };
  add(stimuli);
  for (const auto& g : grids) add(g);
  return key;
}

QuestPlus::Tables QuestPlus::tabulate(const QuestPlusDefinition& d) {
  const size_t n = d.stimuli.size(), points = d.parameter_points();
  Tables t{std::vector<double>(n * points), std::vector<double>(n * points)};
  for_each_index(points, [&](size_t point) {
    const ParameterPoint p = values_at(point, d.grids);
    for (size_t s = 0; s < n; ++s) {
      const double psi = psychometric(d.shape, d.scale, d.stimuli[s], p);
      t.likelihood[s * points + point] = psi;
      t.outcome_entropy[s * points + point] = binary_entropy(psi);
    }
  });
  return t;
}

std::shared_ptr<const QuestPlus::Tables> QuestPlus::shared_tables(const QuestPlusDefinition& d) {
  static std::mutex mutex;
  static std::map<std::string, std::weak_ptr<const Tables>> living;
  const std::string key = d.tables_key();
  {
    std::lock_guard lock(mutex);
    if (auto tables = living[key].lock()) return tables;
  }
  // Made outside the lock: the tabulation runs on the app's threads, which may meanwhile take up
  // another run's construction.
  auto made = std::make_shared<const Tables>(tabulate(d));
  std::lock_guard lock(mutex);
  std::erase_if(living, [](const auto& entry) { return entry.second.expired(); });
  auto& slot = living[key];
  if (auto tables = slot.lock()) return tables;  // another thread made them first
  slot = made;
  return made;
}

QuestPlus::QuestPlus(QuestPlusDefinition definition)
    : definition_(std::move(definition)),
      points_(definition_.parameter_points()),
      tables_(shared_tables(definition_)) {
  posterior_ = joint_prior(definition_, points_);
  entropy_ = posterior_entropy();
}

std::vector<double> QuestPlus::expected_entropies() const {
  const double h = entropy();
  std::vector<double> out(definition_.stimuli.size());
  for_each_index(out.size(), [&](size_t s) {
    const double* l = &tables_->likelihood[s * points_];
    const double* e = &tables_->outcome_entropy[s * points_];
    double correct = 0, within = 0;  // Σ post·ψ and Σ post·h
    for (size_t i = 0; i < points_; ++i) {
      correct += posterior_[i] * l[i];
      within += posterior_[i] * e[i];
    }
    out[s] = h + within - binary_entropy(std::clamp(correct, 0.0, 1.0));
  });
  return out;
}

size_t QuestPlus::next() const {
  const std::vector<double> expected = expected_entropies();
  const double least = *std::min_element(expected.begin(), expected.end());
  for (size_t s = 0; s < expected.size(); ++s)
    if (expected[s] <= least + std::abs(least) * 1e-12) return s;
  return 0;
}

void QuestPlus::update(size_t stimulus, bool first_outcome) {
  multiply(&tables_->likelihood[stimulus * points_], first_outcome);
}

void QuestPlus::update_at(double x, bool first_outcome) {
  std::vector<double> l(points_);
  for (size_t point = 0; point < points_; ++point) {
    const ParameterPoint p = values_at(point, definition_.grids);
    l[point] = psychometric(definition_.shape, definition_.scale, x, p);
  }
  multiply(l.data(), first_outcome);
}

void QuestPlus::multiply(const double* psi, bool first_outcome) {
  ++trials_;
  double sum = 0;
  for (size_t i = 0; i < points_; ++i) sum += posterior_[i] * (first_outcome ? psi[i] : 1 - psi[i]);
  // An answer no parameter point allows (with a lapse rate of 0, a miss where ψ = 1 everywhere)
  // would leave no posterior: it is counted and leaves the posterior as it was.
  if (!(sum > 0)) {
    ++impossible_;
    return;
  }
  for (size_t i = 0; i < points_; ++i)
    posterior_[i] = posterior_[i] * (first_outcome ? psi[i] : 1 - psi[i]) / sum;
  entropy_ = posterior_entropy();
  marginals_.reset();
}

double QuestPlus::posterior_entropy() const {
  double h = 0;
  for (double p : posterior_) h += information(p);
  return h;
}

ParameterPoint QuestPlus::mode() const {
  const size_t best = size_t(std::max_element(posterior_.begin(), posterior_.end()) -
                             posterior_.begin());  // the first maximum
  return values_at(best, definition_.grids);
}

std::array<double, 4> QuestPlus::distribution_of(
    const std::function<double(const ParameterPoint&)>& f) const {
  std::vector<std::pair<double, double>> weighted(points_);  // (value, probability)
  double mean = 0;
  for (size_t point = 0; point < points_; ++point) {
    const ParameterPoint p = values_at(point, definition_.grids);
    weighted[point] = {f(p), posterior_[point]};
    mean += weighted[point].first * weighted[point].second;
  }
  std::sort(weighted.begin(), weighted.end());
  std::array<double, 4> out{f(mode()), mean, weighted.back().first, weighted.back().first};
  double cumulative = 0;
  bool low = false;
  for (const auto& [value, probability] : weighted) {
    cumulative += probability;
    if (!low && cumulative >= 0.025) out[2] = value, low = true;
    if (cumulative >= 0.975) {
      out[3] = value;
      break;
    }
  }
  return out;
}

const std::array<std::vector<double>, kQuestPlusParameters>& QuestPlus::marginals() const {
  if (marginals_) return *marginals_;
  const auto& g = definition_.grids;
  std::array<std::vector<double>, kQuestPlusParameters> m;
  for (size_t k = 0; k < kQuestPlusParameters; ++k) m[k].assign(g[k].size(), 0.0);
  size_t point = 0;  // one pass in the grid's C order
  for (size_t i0 = 0; i0 < g[0].size(); ++i0)
    for (size_t i1 = 0; i1 < g[1].size(); ++i1)
      for (size_t i2 = 0; i2 < g[2].size(); ++i2)
        for (size_t i3 = 0; i3 < g[3].size(); ++i3) {
          const double p = posterior_[point++];
          m[0][i0] += p, m[1][i1] += p, m[2][i2] += p, m[3][i3] += p;
        }
  return *(marginals_ = std::move(m));
}

ParameterPoint QuestPlus::mean() const {
  ParameterPoint out{};
  for (size_t k = 0; k < kQuestPlusParameters; ++k) {
    const std::vector<double>& m = marginals()[k];
    for (size_t i = 0; i < m.size(); ++i) out[k] += definition_.grids[k][i] * m[i];
  }
  return out;
}

ParameterPoint QuestPlus::quantile(double probability) const {
  ParameterPoint out{};
  for (size_t k = 0; k < kQuestPlusParameters; ++k) {
    const std::vector<double>& m = marginals()[k];
    double cumulative = 0;
    size_t i = 0;
    for (; i + 1 < m.size(); ++i)
      if ((cumulative += m[i]) >= probability) break;
    out[k] = definition_.grids[k][i];
  }
  return out;
}

}  // namespace countershade::procedures
