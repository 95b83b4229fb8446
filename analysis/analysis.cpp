#include "analysis/analysis.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "core/error.h"
#include "core/random.h"

namespace countershade::analysis {

double CellTable::sigma_mean(size_t subject, size_t scene, Question q) const {
  double v = 0;
  for (size_t g = 0; g < sigmas_; ++g) v += at(subject, scene, g, q) / double(sigmas_);
  return v;
}

double CellTable::subject_mean(size_t subject, Question q) const {
  double v = 0;
  for (size_t s = 0; s < scenes_; ++s) v += sigma_mean(subject, s, q) / double(scenes_);
  return v;
}

namespace {

using json = nlohmann::ordered_json;
constexpr Question kQuestions[] = {Question::low, Question::high, Question::best};

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
    if (!first)
      first = r;
    else if (std::abs(r->lambda_step - first->lambda_step) > 1e-12)
      throw InputError(r->source + ": lambda_step " + std::to_string(r->lambda_step) +
                       " differs from " + std::to_string(first->lambda_step) + " at " +
                       first->source + " (pass --lambda-step)");
  }
  if (!first) throw InputError("responses have no lambda_step column: pass --lambda-step");
  return first->lambda_step;
}

size_t index_of(const std::vector<std::string>& sorted, const std::string& v) {
  return size_t(std::lower_bound(sorted.begin(), sorted.end(), v) - sorted.begin());
}
size_t index_of(const std::vector<double>& sorted, double v) {
  return size_t(std::lower_bound(sorted.begin(), sorted.end(), v) - sorted.begin());
}

// The scenes and σ of the block, sorted.
void collect_design(BlockResults& b, const std::vector<const Response*>& rows) {
  std::set<std::string> scenes;
  std::set<double> sigmas;
  for (const Response* r : rows) {
    scenes.insert(r->scene);
    sigmas.insert(r->sigma);
  }
  b.scenes.assign(scenes.begin(), scenes.end());
  b.sigmas.assign(sigmas.begin(), sigmas.end());
}

// Each subject's answers per cell, repetitions averaged; subjects with a missing cell or, when
// `needs_low` (subject normalisation), a cell whose mean λ_Low is 0 (no JND scale) are excluded
// with their reason. Returns the included subjects' means.
CellTable subject_means(BlockResults& b, const std::vector<const Response*>& rows, bool needs_low) {
  const size_t ns = b.scenes.size(), nsig = b.sigmas.size();
  std::map<std::string, std::vector<std::vector<double>>> answers;  // subject → cell → answers
  for (const Response* r : rows) {
    auto& cells = answers[r->subject];
    if (cells.empty()) cells.resize(ns * nsig * kQuestionCount);
    cells[(index_of(b.scenes, r->scene) * nsig + index_of(b.sigmas, r->sigma)) * kQuestionCount +
          size_t(r->question)]
        .push_back(r->lambda);
  }
  size_t repeated = 0;
  std::vector<std::vector<double>> included;
  for (const auto& [subject, cells] : answers) {
    std::string reason;
    std::vector<double> means(cells.size());
    for (size_t c = 0; c < cells.size() && reason.empty(); ++c) {
      if (cells[c].empty()) reason = "incomplete design cells";
      repeated += cells[c].size() > 1;
      for (double x : cells[c]) means[c] += x / double(cells[c].size());
    }
    for (size_t s = 0; s < ns && reason.empty() && needs_low; ++s)
      for (size_t g = 0; g < nsig && reason.empty(); ++g)
        if (means[(s * nsig + g) * kQuestionCount + size_t(Question::low)] <= 0)
          reason = "lambda_low of 0 in scene " + b.scenes[s] + ", sigma " +
                   json(b.sigmas[g]).dump() + " (no JND scale)";
    if (!reason.empty()) {
      b.excluded.push_back({subject, reason});
      continue;
    }
    b.subjects.push_back(subject);
    included.push_back(std::move(means));
  }
  if (repeated)
    b.warnings.push_back(std::to_string(repeated) +
                         " cells had repeated answers; they were averaged");
  for (const auto& e : b.excluded)
    b.warnings.push_back("subject " + e.subject + " excluded: " + e.reason);
  CellTable table(included.size(), ns, nsig);
  for (size_t i = 0; i < included.size(); ++i)
    for (size_t s = 0; s < ns; ++s)
      for (size_t g = 0; g < nsig; ++g)
        for (Question q : kQuestions)
          table.at(i, s, g, q) = included[i][(s * nsig + g) * kQuestionCount + size_t(q)];
  return table;
}

// Under group normalisation a scene × σ whose answers to λ_Low are all 0 has no JND scale (every
// JND there would be λ / 0); `where` names the data ("file: method M: ").
void check_group_scale(const BlockResults& b, const CellTable& means, const std::string& where) {
  for (size_t s = 0; s < means.scenes(); ++s)
    for (size_t g = 0; g < means.sigmas(); ++g) {
      bool any = false;
      for (size_t i = 0; i < means.subjects(); ++i) any |= means.at(i, s, g, Question::low) > 0;
      if (!any)
        throw InputError(where + "scene " + b.scenes[s] + ", sigma " + json(b.sigmas[g]).dump() +
                         ": every λ_Low is 0, so --normalization group has no JND scale there");
    }
}

// JND: λ divided by λ_Low of the same subject (or of the group mean) in the same scene × σ.
CellTable jnd_cells(const CellTable& means, JndNormalization normalization) {
  const size_t n = means.subjects(), ns = means.scenes(), nsig = means.sigmas();
  std::vector<double> group_low(ns * nsig, 0.0);
  for (size_t i = 0; i < n; ++i)
    for (size_t s = 0; s < ns; ++s)
      for (size_t g = 0; g < nsig; ++g)
        group_low[s * nsig + g] += means.at(i, s, g, Question::low) / double(n);
  CellTable jnd(n, ns, nsig);
  for (size_t i = 0; i < n; ++i)
    for (size_t s = 0; s < ns; ++s)
      for (size_t g = 0; g < nsig; ++g)
        for (Question q : kQuestions)
          jnd.at(i, s, g, q) = means.at(i, s, g, q) / (normalization == JndNormalization::group
                                                           ? group_low[s * nsig + g]
                                                           : means.at(i, s, g, Question::low));
  return jnd;
}

json summary_json(const Summary& d) {
  return {{"n", d.n}, {"mean", d.mean}, {"sd", d.sd}, {"sem", d.sem}};
}

void add_descriptives(BlockResults& b) {
  const CellTable& jnd = b.jnd;
  json& out = b.json;
  out["descriptives"] = json::array();
  out["descriptives_by_sigma"] = json::array();
  for (size_t s = 0; s < jnd.scenes(); ++s)
    for (Question q : kQuestions) {
      std::vector<double> v;
      for (size_t i = 0; i < jnd.subjects(); ++i) v.push_back(jnd.sigma_mean(i, s, q));
      json row = {{"scene", b.scenes[s]}, {"question", question_name(q)}};
      row.update(summary_json(summarize(v)));
      out["descriptives"].push_back(row);
    }
  for (size_t s = 0; s < jnd.scenes(); ++s)
    for (size_t g = 0; g < jnd.sigmas(); ++g)
      for (Question q : kQuestions) {
        std::vector<double> v;
        for (size_t i = 0; i < jnd.subjects(); ++i) v.push_back(jnd.at(i, s, g, q));
        json row = {{"scene", b.scenes[s]}, {"sigma", b.sigmas[g]}, {"question", question_name(q)}};
        row.update(summary_json(summarize(v)));
        out["descriptives_by_sigma"].push_back(row);
      }
}

// The within factors a design varies: a factor with one level has no effect to test, so it is left
// out. The cells keep their order (a one-level factor adds nothing to a cell's index).
std::vector<WithinFactor> varied_factors(std::vector<WithinFactor> factors) {
  std::erase_if(factors, [](const WithinFactor& f) { return f.levels < 2; });
  return factors;
}

std::string model_name(const std::vector<WithinFactor>& factors) {
  std::string name;
  for (const auto& f : factors) name += (name.empty() ? "" : "*") + f.name;
  return name;
}

// Repeated-measures ANOVAs: question × scene × σ on JND, and scene × σ on λ_Best (JND), each
// over the factors the design varies.
void add_anovas(BlockResults& b) {
  const CellTable& jnd = b.jnd;
  const size_t n = jnd.subjects(), ns = jnd.scenes(), nsig = jnd.sigmas();
  Eigen::MatrixXd full(n, 3 * ns * nsig), best(n, ns * nsig);
  for (size_t i = 0; i < n; ++i)
    for (Question q : kQuestions)
      for (size_t s = 0; s < ns; ++s)
        for (size_t g = 0; g < nsig; ++g) {
          full(long(i), long((size_t(q) * ns + s) * nsig + g)) = jnd.at(i, s, g, q);
          if (q == Question::best) best(long(i), long(s * nsig + g)) = jnd.at(i, s, g, q);
        }
  const auto full_factors =
      varied_factors({{"question", 3}, {"scene", int(ns)}, {"sigma", int(nsig)}});
  const auto best_factors = varied_factors({{"scene", int(ns)}, {"sigma", int(nsig)}});
  if (ns < 2 || nsig < 2)
    b.warnings.push_back(std::string(ns < 2 ? "one scene" : "one σ value") +
                         (ns < 2 && nsig < 2 ? " and one σ value" : "") +
                         ": the ANOVAs leave out the factor with one level");
  b.anova = rm_anova(full, full_factors);
  if (!best_factors.empty()) b.anova_best_sigma = rm_anova(best, best_factors);
  b.json["anova"] = anova_json(model_name(full_factors), b.anova);
  b.json["anova_best_sigma"] = anova_json(
      best_factors.empty() ? "" : model_name(best_factors) + " (best only)", b.anova_best_sigma);
  for (const std::vector<AnovaRow>* rows : {&b.anova, &b.anova_best_sigma})
    for (const AnovaRow& r : *rows)
      if (r.df1 > 1 && !r.has_sphericity)
        b.warnings.push_back(r.effect + ": " + std::to_string(n) +
                             " subjects are too few for a sphericity test of " +
                             std::to_string(int(r.df1)) + " contrasts (at least " +
                             std::to_string(int(r.df1) + 1) +
                             " needed): no Mauchly test and no ε corrections, as in R");
}

// Paired t-tests between the questions on subject means, and λ_Best against 1 JND per scene,
// each family Holm-corrected.
void add_t_tests(BlockResults& b) {
  const CellTable& jnd = b.jnd;
  const size_t n = jnd.subjects(), ns = jnd.scenes();
  const std::pair<Question, Question> pairs[] = {{Question::best, Question::low},
                                                 {Question::high, Question::best},
                                                 {Question::high, Question::low}};
  std::vector<TTest> tests;
  std::vector<double> ps;
  for (auto [a, c] : pairs) {
    std::vector<double> d;
    for (size_t i = 0; i < n; ++i) d.push_back(jnd.subject_mean(i, a) - jnd.subject_mean(i, c));
    tests.push_back(t_test(d, 0.0));
    ps.push_back(tests.back().p);
  }
  auto adjusted = holm(ps);
  b.json["pairwise"] = json::array();
  for (size_t k = 0; k < 3; ++k)
    b.json["pairwise"].push_back({{"a", question_name(pairs[k].first)},
                                  {"b", question_name(pairs[k].second)},
                                  {"mean_diff", tests[k].mean},
                                  {"t", tests[k].t},
                                  {"df", tests[k].df},
                                  {"p", tests[k].p},
                                  {"p_holm", adjusted[k]}});
  tests.clear();
  ps.clear();
  for (size_t s = 0; s < ns; ++s) {
    std::vector<double> v;
    for (size_t i = 0; i < n; ++i) v.push_back(jnd.sigma_mean(i, s, Question::best));
    tests.push_back(t_test(v, 1.0));
    ps.push_back(tests.back().p);
  }
  adjusted = holm(ps);
  b.json["best_vs_threshold"] = json::array();
  for (size_t s = 0; s < ns; ++s)
    b.json["best_vs_threshold"].push_back({{"scene", b.scenes[s]},
                                           {"mean", tests[s].mean},
                                           {"t", tests[s].t},
                                           {"df", tests[s].df},
                                           {"p", tests[s].p},
                                           {"p_holm", adjusted[s]}});
}

// A statistic that is not finite means that the answers it compares do not vary between subjects
// (an error variance of 0): say so, since its p-value (0, or NA for 0 / 0) rests on nothing.
void warn_about_constant_data(BlockResults& b) {
  const std::pair<const char*, const char*> tables[] = {
      {"anova", "F"}, {"anova_best_sigma", "F"}, {"pairwise", "t"}, {"best_vs_threshold", "t"}};
  for (const auto& [table, statistic] : tables)
    for (const json& row : b.json[table]) {
      const double value = row[statistic].get<double>();
      if (std::isfinite(value)) continue;
      const std::string name = row.contains("effect")  ? row["effect"].get<std::string>()
                               : row.contains("scene") ? row["scene"].get<std::string>()
                                                       : row["a"].get<std::string>() + " − " +
                                                             row["b"].get<std::string>();
      b.warnings.push_back(std::string(table) + " " + name + ": " + statistic + " = " +
                           (std::isnan(value) ? "NA" : "Inf") +
                           ", the answers do not vary between subjects (an error variance of 0)");
    }
}

// Ward clusters of subjects by their per-scene λ_Best.
void add_clusters(BlockResults& b, int clusters) {
  const CellTable& jnd = b.jnd;
  const size_t n = jnd.subjects(), ns = jnd.scenes();
  Eigen::MatrixXd prefs(n, ns);
  for (size_t i = 0; i < n; ++i)
    for (size_t s = 0; s < ns; ++s) prefs(long(i), long(s)) = jnd.sigma_mean(i, s, Question::best);
  const int k = std::clamp(clusters, 1, int(n));
  if (k != clusters)
    b.warnings.push_back("--clusters " + std::to_string(clusters) + " lowered to " +
                         std::to_string(k) + " (the number of subjects)");
  b.dendrogram = ward_d2(prefs);
  b.cluster_labels = cut_tree(b.dendrogram, int(n), k);
  json assignments = json::object();
  std::vector<int> sizes(size_t(k), 0);
  std::vector<double> mean_best(size_t(k), 0.0);
  for (size_t i = 0; i < n; ++i) {
    const int label = b.cluster_labels[i];
    assignments[b.subjects[i]] = label;
    sizes[size_t(label - 1)]++;
    mean_best[size_t(label - 1)] += prefs.row(long(i)).mean();
  }
  for (int c = 0; c < k; ++c) mean_best[size_t(c)] /= std::max(1, sizes[size_t(c)]);
  b.json["clusters"] = {
      {"method", "ward.D2"},        {"distance", "euclidean"}, {"k", k},
      {"assignments", assignments}, {"sizes", sizes},          {"mean_best", mean_best}};
}

json fit_json(const BlockResults::FitEntry& entry, const AnalysisOptions& options) {
  json f = {{"scene", entry.scene},
            {"sigma", entry.sigma},
            {"question", question_name(entry.question)},
            {"model", threshold_model_name(options.model)},
            {"threshold", entry.fit.threshold},
            {"log_threshold", entry.fit.log_threshold},
            {"log_threshold_se", entry.fit.log_threshold_se},
            {"log_sd", entry.fit.scale},
            {"n", entry.fit.n},
            {"left_censored", entry.fit.left_censored},
            {"right_censored", entry.fit.right_censored},
            {"identified", entry.fit.identified},
            {"converged", entry.fit.converged}};
  if (options.bootstrap > 0) {
    f["ci_low"] = entry.fit.ci_low;
    f["ci_high"] = entry.fit.ci_high;
    f["bootstrap"] = entry.fit.bootstrap;
  }
  return f;
}

// A cell's answers as intervals (methods.md, threshold fits), its grid for the bootstrap, and
// how many answers were λ = 0.
struct CellAnswers {
  std::vector<AnswerInterval> intervals;
  AnswerGrid grid;
  size_t zeros = 0;
};

CellAnswers cell_answers(const std::vector<const Response*>& cell, double step) {
  CellAnswers out;
  out.grid.step = step;
  out.grid.first = step;  // without lambda_index, the grid's first value is taken as one step
  bool first_known = false;
  for (const Response* r : cell) {
    bool zero = false;
    out.intervals.push_back(
        answer_interval(r->lambda, r->lambda_index, step, r->lambda_max, &zero));
    out.zeros += zero;
    if (r->lambda_index >= 0) {
      const double first = r->lambda - r->lambda_index * step;
      out.grid.first = first_known ? std::min(out.grid.first, first) : first;
      first_known = true;
    }
    if (r->lambda_max > 0)
      out.grid.top =
          std::isinf(out.grid.top) ? r->lambda_max : std::max(out.grid.top, r->lambda_max);
  }
  return out;
}

std::string cell_name(const BlockResults::FitEntry& e) {
  return e.scene + ", sigma " + json(e.sigma).dump() + ", " + question_name(e.question);
}

void fit_cell(BlockResults& b, BlockResults::FitEntry& entry, const CellAnswers& cell,
              const AnalysisOptions& options) {
  if (cell.zeros)
    b.warnings.push_back(std::to_string(cell.zeros) +
                         " answers of lambda = 0 counted as (0, lambda_1]: " + cell_name(entry));
  entry.fit = fit_threshold(cell.intervals, options.model);
  if (entry.fit.one_step)
    b.warnings.push_back(
        "fit unidentified (every answer at one grid step, or on the two sides of one step "
        "boundary: no spread to fit, no standard error; the threshold is that step): " +
        cell_name(entry));
  else if (!entry.fit.identified)
    b.warnings.push_back("fit unidentified (every answer censored at the " +
                         std::string(entry.fit.left_censored == entry.fit.n ? "bottom" : "top") +
                         " of the grid): " + cell_name(entry));
  else if (!entry.fit.converged)
    b.warnings.push_back("fit did not converge: " + cell_name(entry));
  if (options.bootstrap > 0)
    bootstrap_threshold(entry.fit, cell.grid, options.bootstrap,
                        hash_combine(options.seed, uint64_t(b.fits.size())));
}

// Threshold fits on the raw answers of the included subjects (repetitions kept).
void add_fits(BlockResults& b, const std::vector<const Response*>& rows,
              const AnalysisOptions& options) {
  const std::set<std::string> included(b.subjects.begin(), b.subjects.end());
  if (std::none_of(rows.begin(), rows.end(), [](const Response* r) { return r->lambda_max > 0; }))
    b.warnings.push_back(
        "no lambda_max column: no answer is right-censored at the top of the grid");
  b.json["fits"] = json::array();
  for (size_t s = 0; s < b.scenes.size(); ++s)
    for (size_t g = 0; g < b.sigmas.size(); ++g)
      for (Question q : kQuestions) {
        BlockResults::FitEntry entry{b.scenes[s], b.sigmas[g], q, {}, {}};
        std::vector<const Response*> cell;
        for (const Response* r : rows)
          if (included.count(r->subject) && r->scene == entry.scene && r->sigma == entry.sigma &&
              r->question == q) {
            cell.push_back(r);
            entry.answers.push_back(r->lambda);
          }
        fit_cell(b, entry, cell_answers(cell, b.lambda_step), options);
        b.json["fits"].push_back(fit_json(entry, options));
        b.fits.push_back(std::move(entry));
      }
}

// "file: method M: ", the start of an error about a block's data.
std::string data_name(const std::vector<const Response*>& rows, const std::string& method) {
  const std::string& source = rows.front()->source;  // "file:line"
  return source.substr(0, source.rfind(':')) + ": " +
         (method.empty() ? "" : "method " + method + ": ");
}

BlockResults analyze_block(const std::string& method, const std::vector<const Response*>& rows,
                           const AnalysisOptions& options) {
  BlockResults b;
  b.method = method;
  b.lambda_step = resolve_step(rows, options);
  collect_design(b, rows);
  // Dividing by a subject's own λ_Low needs it positive; the group mean does not.
  const CellTable means =
      subject_means(b, rows, options.normalization == JndNormalization::subject);
  b.lambda_means = means;
  const size_t n = b.subjects.size();
  if (n < 3) {
    const std::string example = b.excluded.empty() ? ""
                                                   : ", e.g. " + b.excluded.front().subject + ": " +
                                                         b.excluded.front().reason;
    throw InputError(data_name(rows, method) + "only " + std::to_string(n) +
                     (n == 1 ? " subject has" : " subjects have") +
                     " answers in every cell (need 3 or more; " +
                     std::to_string(b.excluded.size()) + " excluded" + example + ")");
  }
  if (options.normalization == JndNormalization::group)
    check_group_scale(b, means, data_name(rows, method));
  b.jnd = jnd_cells(means, options.normalization);

  json& out = b.json;
  out["n_subjects"] = n;
  out["excluded_subjects"] = json::array();
  for (const auto& e : b.excluded)
    out["excluded_subjects"].push_back({{"subject", e.subject}, {"reason", e.reason}});
  out["lambda_step"] = b.lambda_step;
  out["jnd_normalization"] = jnd_normalization_name(options.normalization);
  b.browser_answers =
      size_t(std::count_if(rows.begin(), rows.end(), [](const Response* r) { return r->browser; }));
  if (!method.empty()) out["method"] = method;
  add_descriptives(b);
  add_anovas(b);
  add_t_tests(b);
  warn_about_constant_data(b);
  add_clusters(b, options.clusters);
  add_fits(b, rows, options);
  out["warnings"] = b.warnings;
  return b;
}

}  // namespace

JndNormalization parse_jnd_normalization(const std::string& name) {
  if (name == "subject") return JndNormalization::subject;
  if (name == "group") return JndNormalization::group;
  throw InputError("--normalization: expected subject or group, got '" + name + "'");
}

const char* jnd_normalization_name(JndNormalization normalization) {
  return normalization == JndNormalization::group ? "group" : "subject";
}

std::vector<BlockResults> analyze(const std::vector<Response>& responses,
                                  const AnalysisOptions& options) {
  if (options.lambda_step && !(*options.lambda_step > 0))
    throw InputError("--lambda-step: must be positive");
  std::map<std::string, std::vector<const Response*>> blocks;
  for (const auto& r : responses) blocks[r.method].push_back(&r);
  std::vector<BlockResults> results;
  for (const auto& [method, rows] : blocks) results.push_back(analyze_block(method, rows, options));
  return results;
}

}  // namespace countershade::analysis
