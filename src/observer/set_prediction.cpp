#include "observer/set_prediction.h"

#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <tuple>

#include "core/parallel.h"
#include "observer/luminance_image.h"

namespace countershade::observer {
namespace {

// One condition's still images, ascending in λ, and its scene's reference.
struct ConditionImages {
  const ManifestEntry* reference = nullptr;
  std::vector<const ManifestEntry*> stimuli;
};

using ConditionKey = std::tuple<std::string, std::string, double>;  // scene, condition, σ

ConditionKey key_of(const ManifestEntry& e) {
  return {e.scene, e.condition_method(), e.sigma.value_or(0)};
}

// The still conditions by scene, condition and σ; sequence conditions are counted in `skipped`.
std::vector<std::pair<ConditionKey, ConditionImages>> still_conditions(const Manifest& manifest,
                                                                       size_t& skipped) {
  std::map<std::string, const ManifestEntry*> references;
  for (const auto& e : manifest.stimuli)
    if (e.is_reference() && !e.frame) references[e.scene] = &e;
  std::vector<std::pair<ConditionKey, ConditionImages>> out;
  std::map<ConditionKey, size_t> index;
  std::set<ConditionKey> sequences;
  for (const auto& e : manifest.stimuli) {
    if (e.is_reference()) continue;
    const ConditionKey key = key_of(e);
    if (e.frame || !references.count(e.scene)) {
      sequences.insert(key);
      continue;
    }
    auto [it, added] = index.emplace(key, out.size());
    if (added) out.push_back({key, {references[e.scene], {}}});
    out[it->second].second.stimuli.push_back(&e);
  }
  for (auto& [key, images] : out)
    std::stable_sort(
        images.stimuli.begin(), images.stimuli.end(),
        [](const ManifestEntry* a, const ManifestEntry* b) { return a->lambda < b->lambda; });
  skipped = sequences.size();
  // The manifest lists files by name, which puts σ 16 before σ 8; a reader expects numbers.
  std::stable_sort(out.begin(), out.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  return out;
}

// What every image of a set is compared with: its scene's reference luminance, and the filter
// for its size (made once per size).
class SetContext {
 public:
  SetContext(const std::filesystem::path& dir, const PredictionSettings& settings)
      : dir_(dir), settings_(settings) {}

  ContrastImage filtered(const ManifestEntry& stimulus, const ManifestEntry& reference) {
    const LuminanceImage& ref = reference_luminance(reference);
    const std::string file = resolve_in_set(dir_, stimulus.file).string();
    const LuminanceImage test = read_luminance(file, settings_.display);
    const ContrastImage contrast =
        contrast_between(ref, test, resolve_in_set(dir_, reference.file).string(), file);
    return filter_for(contrast.width, contrast.height).apply(contrast);
  }

 private:
  const LuminanceImage& reference_luminance(const ManifestEntry& reference) {
    const std::lock_guard<std::mutex> lock(mutex_);
    auto& slot = references_[reference.file];
    if (!slot)
      slot = std::make_unique<LuminanceImage>(
          read_luminance(resolve_in_set(dir_, reference.file).string(), settings_.display));
    return *slot;
  }
  const CsfFilter& filter_for(int width, int height) {
    const std::lock_guard<std::mutex> lock(mutex_);
    auto& slot = filters_[{width, height}];
    if (!slot)
      slot = std::make_unique<CsfFilter>(width, height, settings_.ppd, settings_.model.oblique);
    return *slot;
  }

  std::filesystem::path dir_;
  const PredictionSettings& settings_;
  std::mutex mutex_;
  std::map<std::string, std::unique_ptr<LuminanceImage>> references_;
  std::map<std::pair<int, int>, std::unique_ptr<CsfFilter>> filters_;
};

// The λ at each level: the first grid step at or above it, refined between its images.
void find_levels(ConditionPrediction& p, const ConditionImages& images, SetContext& context,
                 const PredictionSettings& settings) {
  // The levels often fall between the same two grid images (a set whose first step is already
  // above 4 JND): each image is filtered once.
  std::map<size_t, ContrastImage> filtered;
  auto filtered_at = [&](size_t i) -> const ContrastImage& {
    auto [it, added] = filtered.try_emplace(i);
    if (added) it->second = context.filtered(*images.stimuli[i], *images.reference);
    return it->second;
  };
  for (size_t l = 0; l < kPredictionLevels.size(); ++l) {
    const double level = kPredictionLevels[l];
    size_t i = 0;
    while (i < p.jnd.size() && p.jnd[i] < level) ++i;
    if (i == p.jnd.size()) continue;
    if (i == 0) {
      p.lambda_at[l] = p.lambda[0];
      continue;
    }
    p.lambda_at[l] = lambda_reaching(level, filtered_at(i - 1), p.lambda[i - 1], filtered_at(i),
                                     p.lambda[i], settings.ppd, settings.model);
  }
}

}  // namespace

double lambda_reaching(double level, const ContrastImage& filtered_a, double lambda_a,
                       const ContrastImage& filtered_b, double lambda_b, double ppd,
                       const DetectionModel& model) {
  ContrastImage mix = filtered_a;
  auto excess = [&](double t) {
    for (size_t k = 0; k < mix.values.size(); ++k)
      mix.values[k] = filtered_a.values[k] + t * (filtered_b.values[k] - filtered_a.values[k]);
    return filtered_response_jnd(mix, ppd, model) - level;
  };
  // Regula falsi with the Illinois step: the response is a norm of an affine function of t, so
  // convex, and this converges in a few evaluations, each a pass over the image.
  double t0 = 0, t1 = 1, f0 = excess(0), f1 = excess(1);
  for (int iteration = 0; iteration < 40 && f1 != 0; ++iteration) {
    const double t = t1 - f1 * (t1 - t0) / (f1 - f0);
    const double f = excess(t);
    if (std::abs(f) < 1e-6 * level) return lambda_a + t * (lambda_b - lambda_a);
    if ((f < 0) == (f0 < 0)) {
      t0 = t;
      f0 = f;
      f1 *= 0.5;
    } else {
      t1 = t;
      f1 = f;
      f0 *= 0.5;
    }
  }
  return lambda_a + t1 * (lambda_b - lambda_a);
}

SetPrediction predict_set(const Manifest& manifest, const std::filesystem::path& set_dir,
                          const PredictionSettings& settings) {
  SetPrediction out;
  const auto conditions = still_conditions(manifest, out.sequence_conditions_skipped);
  std::vector<std::pair<size_t, size_t>> jobs;  // (condition, image)
  for (const auto& [key, images] : conditions) {
    ConditionPrediction p;
    std::tie(p.scene, p.method, p.sigma) = key;
    for (size_t i = 0; i < images.stimuli.size(); ++i) {
      jobs.push_back({out.conditions.size(), i});
      p.lambda.push_back(images.stimuli[i]->lambda);
    }
    p.jnd.assign(p.lambda.size(), 0.0);
    out.conditions.push_back(std::move(p));
  }
  SetContext context(set_dir, settings);
  std::atomic<size_t> done{0};
  parallel_ranges(jobs.size(), settings.threads, [&](size_t begin, size_t end) {
    for (size_t j = begin; j < end; ++j) {
      const auto [c, i] = jobs[j];
      const ConditionImages& images = conditions[c].second;
      out.conditions[c].jnd[i] = filtered_response_jnd(
          context.filtered(*images.stimuli[i], *images.reference), settings.ppd, settings.model);
      if (settings.progress) settings.progress(double(++done) / double(jobs.size()));
    }
  });
  parallel_ranges(conditions.size(), settings.threads, [&](size_t begin, size_t end) {
    for (size_t c = begin; c < end; ++c)
      find_levels(out.conditions[c], conditions[c].second, context, settings);
  });
  return out;
}

}  // namespace countershade::observer
