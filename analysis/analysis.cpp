#include "analysis/analysis.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "core/error.h"
#include "core/random.h"

namespace countershade::analysis {
namespace {

using json = nlohmann::ordered_json;

json anova_json(const std::string& model, const std::vector<AnovaRow>& rows) {
  json out = json::array();
  for (const auto& r : rows) {
    json row = {{"model", model}, {"effect", r.effect}, {"df1", r.df1}, {"df2", r.df2},
                {"F", r.F},       {"p", r.p},           {"ges", r.ges}};
    if (r.has_sphericity) {
      row["mauchly_W"] = r.mauchly_W;
      row["mauchly_p"] = r.mauchly_p;
      row["gg_epsilon"] = r.gg_epsilon;
      row["p_gg"] = r.p_gg;
      row["hf_epsilon"] = r.hf_epsilon;
      row["p_hf"] = r.p_hf;
    }
    out.push_back(row);
  }
  return out;
}

double resolve_step(const std::vector<const Response*>& rows, const AnalysisOptions& options) {
  if (options.lambda_step) return *options.lambda_step;
  const Response* first = nullptr;
  for (const Response* r : rows) {
    if (r->lambda_step <= 0) continue;
    if (!first) first = r;
    else if (std::abs(r->lambda_step - first->lambda_step) > 1e-12)
      throw InputError(r->source + ": lambda_step " + std::to_string(r->lambda_step) + " differs from " +
                       std::to_string(first->lambda_step) + " at " + first->source + " (pass --lambda-step)");
  }
  if (!first) throw InputError("responses have no lambda_step column: pass --lambda-step");
  return first->lambda_step;
}

BlockResults analyze_block(const std::string& method, const std::vector<const Response*>& rows,
                           const AnalysisOptions& options) {
  BlockResults b;
  b.method = method;
  b.lambda_step = resolve_step(rows, options);
  std::set<std::string> subjects, scenes;
  std::set<double> sigmas;
  for (const Response* r : rows) {
    subjects.insert(r->subject);
    scenes.insert(r->scene);
    sigmas.insert(r->sigma);
  }
  b.scenes.assign(scenes.begin(), scenes.end());
  b.sigmas.assign(sigmas.begin(), sigmas.end());
  const size_t ns = b.scenes.size(), nsig = b.sigmas.size();
  auto scene_index = [&](const std::string& s) { return size_t(std::lower_bound(b.scenes.begin(), b.scenes.end(), s) - b.scenes.begin()); };
  auto sigma_index = [&](double s) { return size_t(std::lower_bound(b.sigmas.begin(), b.sigmas.end(), s) - b.sigmas.begin()); };

  // Answers per subject and cell; repetitions are averaged.
  std::map<std::string, std::vector<std::vector<std::array<std::vector<double>, 3>>>> answers;
  for (const Response* r : rows) {
    auto& cells = answers[r->subject];
    if (cells.empty()) cells.assign(ns, std::vector<std::array<std::vector<double>, 3>>(nsig));
    cells[scene_index(r->scene)][sigma_index(r->sigma)][int(r->question)].push_back(r->lambda);
  }
  size_t repeated = 0;
  std::map<std::string, std::vector<std::vector<std::array<double, 3>>>> means;
  for (const auto& [subject, cells] : answers) {
    std::string reason;
    auto& m = means[subject];
    m.assign(ns, std::vector<std::array<double, 3>>(nsig));
    for (size_t s = 0; s < ns && reason.empty(); ++s)
      for (size_t g = 0; g < nsig && reason.empty(); ++g)
        for (int q = 0; q < 3; ++q) {
          const auto& v = cells[s][g][q];
          if (v.empty()) {
            reason = "incomplete design cells";
            break;
          }
          repeated += v.size() > 1;
          double mean = 0;
          for (double x : v) mean += x / double(v.size());
          m[s][g][q] = mean;
        }
    if (reason.empty())
      for (size_t s = 0; s < ns && reason.empty(); ++s)
        for (size_t g = 0; g < nsig; ++g)
          if (m[s][g][0] <= 0) {
            reason = "lambda_low of 0 in scene " + b.scenes[s] + ", sigma " + json(b.sigmas[g]).dump() +
                     " (no JND scale)";
            break;
          }
    if (reason.empty()) b.subjects.push_back(subject);
    else b.excluded.push_back({subject, reason});
  }
  if (repeated) b.warnings.push_back(std::to_string(repeated) + " cells had repeated answers; they were averaged");
  for (const auto& e : b.excluded) b.warnings.push_back("subject " + e.subject + " excluded: " + e.reason);
  const size_t n = b.subjects.size();
  if (n < 3) throw InputError("method block '" + method + "': only " + std::to_string(n) + " complete subjects (need 3 or more)");

  // JND: divide by λ_Low of the same subject (or of the group mean) in the same scene × σ.
  std::vector<std::vector<double>> group_low(ns, std::vector<double>(nsig, 0.0));
  for (const auto& subject : b.subjects)
    for (size_t s = 0; s < ns; ++s)
      for (size_t g = 0; g < nsig; ++g) group_low[s][g] += means[subject][s][g][0] / double(n);
  b.jnd.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const auto& m = means[b.subjects[i]];
    b.jnd[i] = m;
    for (size_t s = 0; s < ns; ++s)
      for (size_t g = 0; g < nsig; ++g)
        for (int q = 0; q < 3; ++q)
          b.jnd[i][s][g][q] = m[s][g][q] / (options.normalization == "group" ? group_low[s][g] : m[s][g][0]);
  }
  auto sigma_mean = [&](size_t i, size_t s, int q) {
    double v = 0;
    for (size_t g = 0; g < nsig; ++g) v += b.jnd[i][s][g][q] / double(nsig);
    return v;
  };

  json& out = b.json;
  out["n_subjects"] = n;
  out["excluded_subjects"] = json::array();
  for (const auto& e : b.excluded) out["excluded_subjects"].push_back({{"subject", e.subject}, {"reason", e.reason}});
  out["lambda_step"] = b.lambda_step;
  out["jnd_normalization"] = options.normalization;
  if (!method.empty()) out["method"] = method;

  // Descriptives.
  out["descriptives"] = json::array();
  out["descriptives_by_sigma"] = json::array();
  for (size_t s = 0; s < ns; ++s)
    for (int q = 0; q < 3; ++q) {
      std::vector<double> v;
      for (size_t i = 0; i < n; ++i) v.push_back(sigma_mean(i, s, q));
      Summary d = summarize(v);
      out["descriptives"].push_back({{"scene", b.scenes[s]}, {"question", kQuestionNames[q]}, {"n", d.n},
                                     {"mean", d.mean}, {"sd", d.sd}, {"sem", d.sem}});
    }
  for (size_t s = 0; s < ns; ++s)
    for (size_t g = 0; g < nsig; ++g)
      for (int q = 0; q < 3; ++q) {
        std::vector<double> v;
        for (size_t i = 0; i < n; ++i) v.push_back(b.jnd[i][s][g][q]);
        Summary d = summarize(v);
        out["descriptives_by_sigma"].push_back({{"scene", b.scenes[s]}, {"sigma", b.sigmas[g]},
                                                {"question", kQuestionNames[q]}, {"n", d.n}, {"mean", d.mean},
                                                {"sd", d.sd}, {"sem", d.sem}});
      }

  // Repeated-measures ANOVAs: question × scene × σ on JND, and scene × σ on λ_Best (JND).
  Eigen::MatrixXd full(n, 3 * ns * nsig), best(n, ns * nsig);
  for (size_t i = 0; i < n; ++i)
    for (int q = 0; q < 3; ++q)
      for (size_t s = 0; s < ns; ++s)
        for (size_t g = 0; g < nsig; ++g) {
          full(long(i), long((size_t(q) * ns + s) * nsig + g)) = b.jnd[i][s][g][q];
          if (q == int(Question::best)) best(long(i), long(s * nsig + g)) = b.jnd[i][s][g][q];
        }
  if (ns < 2 || nsig < 2) b.warnings.push_back("fewer than two scenes or σ values: ANOVAs with one level are skipped");
  else {
    b.anova = rm_anova(full, {{"question", 3}, {"scene", int(ns)}, {"sigma", int(nsig)}});
    b.anova_best_sigma = rm_anova(best, {{"scene", int(ns)}, {"sigma", int(nsig)}});
  }
  out["anova"] = anova_json("question*scene*sigma", b.anova);
  out["anova_best_sigma"] = anova_json("scene*sigma (best only)", b.anova_best_sigma);

  // Paired t-tests between the questions on subject means, Holm-corrected.
  auto subject_mean = [&](size_t i, int q) {
    double v = 0;
    for (size_t s = 0; s < ns; ++s) v += sigma_mean(i, s, q) / double(ns);
    return v;
  };
  const std::pair<Question, Question> pairs[] = {
      {Question::best, Question::low}, {Question::high, Question::best}, {Question::high, Question::low}};
  std::vector<TTest> tests;
  for (auto [a, c] : pairs) {
    std::vector<double> d;
    for (size_t i = 0; i < n; ++i) d.push_back(subject_mean(i, int(a)) - subject_mean(i, int(c)));
    tests.push_back(t_test(d, 0.0));
  }
  std::vector<double> ps;
  for (const auto& t : tests) ps.push_back(t.p);
  auto adjusted = holm(ps);
  out["pairwise"] = json::array();
  for (size_t k = 0; k < 3; ++k)
    out["pairwise"].push_back({{"a", kQuestionNames[int(pairs[k].first)]}, {"b", kQuestionNames[int(pairs[k].second)]},
                               {"mean_diff", tests[k].mean}, {"t", tests[k].t}, {"df", tests[k].df},
                               {"p", tests[k].p}, {"p_holm", adjusted[k]}});

  // λ_Best against 1 JND per scene, Holm-corrected across scenes.
  tests.clear();
  ps.clear();
  for (size_t s = 0; s < ns; ++s) {
    std::vector<double> v;
    for (size_t i = 0; i < n; ++i) v.push_back(sigma_mean(i, s, int(Question::best)));
    tests.push_back(t_test(v, 1.0));
    ps.push_back(tests.back().p);
  }
  adjusted = holm(ps);
  out["best_vs_threshold"] = json::array();
  for (size_t s = 0; s < ns; ++s)
    out["best_vs_threshold"].push_back({{"scene", b.scenes[s]}, {"mean", tests[s].mean}, {"t", tests[s].t},
                                        {"df", tests[s].df}, {"p", tests[s].p}, {"p_holm", adjusted[s]}});

  // Ward clusters of subjects by their per-scene λ_Best.
  Eigen::MatrixXd prefs(n, ns);
  for (size_t i = 0; i < n; ++i)
    for (size_t s = 0; s < ns; ++s) prefs(long(i), long(s)) = sigma_mean(i, s, int(Question::best));
  int k = std::clamp(options.clusters, 1, int(n));
  b.dendrogram = ward_d2(prefs);
  b.cluster_labels = cut_tree(b.dendrogram, int(n), k);
  json assignments = json::object();
  std::vector<int> sizes(size_t(k), 0);
  std::vector<double> mean_best(size_t(k), 0.0);
  for (size_t i = 0; i < n; ++i) {
    int label = b.cluster_labels[i];
    assignments[b.subjects[i]] = label;
    sizes[size_t(label - 1)]++;
    mean_best[size_t(label - 1)] += prefs.row(long(i)).mean();
  }
  for (int c = 0; c < k; ++c) mean_best[size_t(c)] /= std::max(1, sizes[size_t(c)]);
  out["clusters"] = {{"method", "ward.D2"}, {"distance", "euclidean"}, {"k", k},
                     {"assignments", assignments}, {"sizes", sizes}, {"mean_best", mean_best}};

  // Threshold fits on the raw answers of the included subjects (repetitions kept).
  std::set<std::string> included(b.subjects.begin(), b.subjects.end());
  out["fits"] = json::array();
  for (size_t s = 0; s < ns; ++s)
    for (size_t g = 0; g < nsig; ++g)
      for (int q = 0; q < 3; ++q) {
        BlockResults::FitEntry entry{b.scenes[s], b.sigmas[g], Question(q), {}, {}};
        for (const Response* r : rows)
          if (included.count(r->subject) && r->scene == entry.scene && r->sigma == entry.sigma && int(r->question) == q)
            entry.answers.push_back(r->lambda);
        entry.fit = fit_threshold(entry.answers, b.lambda_step, options.model);
        if (!entry.fit.converged)
          b.warnings.push_back("fit did not converge: " + entry.scene + ", sigma " + json(entry.sigma).dump() + ", " +
                               kQuestionNames[q]);
        if (options.bootstrap > 0)
          bootstrap_threshold(entry.fit, b.lambda_step, options.bootstrap,
                              hash_combine(options.seed, uint64_t(b.fits.size())));
        json f = {{"scene", entry.scene},          {"sigma", entry.sigma},
                  {"question", kQuestionNames[q]}, {"model", fit_model_name(options.model)},
                  {"threshold", entry.fit.threshold}, {"log_threshold", entry.fit.log_threshold},
                  {"log_threshold_se", entry.fit.log_threshold_se}, {"log_sd", entry.fit.scale},
                  {"n", entry.fit.n},              {"converged", entry.fit.converged}};
        if (options.bootstrap > 0) {
          f["ci_low"] = entry.fit.ci_low;
          f["ci_high"] = entry.fit.ci_high;
          f["bootstrap"] = entry.fit.bootstrap;
        }
        out["fits"].push_back(f);
        b.fits.push_back(std::move(entry));
      }
  out["warnings"] = b.warnings;
  return b;
}

}  // namespace

std::vector<BlockResults> analyze(const std::vector<Response>& responses, const AnalysisOptions& options) {
  if (options.normalization != "subject" && options.normalization != "group")
    throw InputError("--normalization: expected subject or group");
  if (options.lambda_step && !(*options.lambda_step > 0)) throw InputError("--lambda-step: must be positive");
  std::map<std::string, std::vector<const Response*>> blocks;
  for (const auto& r : responses) blocks[r.method].push_back(&r);
  std::vector<BlockResults> results;
  for (const auto& [method, rows] : blocks) results.push_back(analyze_block(method, rows, options));
  return results;
}

}  // namespace countershade::analysis
