#pragma once
// QUEST+ (Watson 2017): a posterior over a grid of psychometric-function parameters (threshold,
// slope, lower asymptote, lapse rate), updated after each answer, and the next stimulus chosen to
// minimise the expected entropy of the posterior. The conventions are those of the questplus
// package (docs/forced-choice.md, "QUEST+"), so that a run here equals a run there trial by trial.
//
// The likelihood of the first outcome ("Correct") is tabulated once for every stimulus and
// parameter point, with its binary entropy. The expected entropy of a stimulus x then needs two
// sums over the posterior: with p = Σ post·L(x) and h(x) = −L ln L − (1 − L) ln(1 − L),
//   EH(x) = H(post) + Σ post·h(x) − (−p ln p − (1 − p) ln(1 − p)),
// the expansion of Σ_r p_r H_r over the two outcomes.

#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace countershade::procedures {

enum class PsychometricShape { weibull, norm_cdf };
enum class StimulusScale { log10, decibel, linear };

// The four parameters, in this order: threshold (norm_cdf: mean), slope (norm_cdf: sd), lower
// asymptote (the guess rate), lapse rate.
inline constexpr size_t kQuestPlusParameters = 4;
using ParameterPoint = std::array<double, kQuestPlusParameters>;

// The names a procedure file gives the parameters, in the order above.
std::array<std::string, kQuestPlusParameters> parameter_names(PsychometricShape shape);

// ψ(x): the probability of the first outcome at stimulus x (in the scale's units).
double psychometric(PsychometricShape shape, StimulusScale scale, double x,
                    const ParameterPoint& p);

struct QuestPlusDefinition {
  PsychometricShape shape = PsychometricShape::weibull;
  StimulusScale scale = StimulusScale::log10;
  std::vector<double> stimuli;  // the stimulus domain, in the scale's units
  std::array<std::vector<double>, kQuestPlusParameters> grids;
  // Prior weights per parameter, one per grid value; empty: uniform. The joint prior is their
  // outer product, normalised.
  std::array<std::vector<double>, kQuestPlusParameters> prior;

  size_t parameter_points() const;
  // The memory the tables and the posterior take, bytes (as doubles: they may not fit a size_t).
  double table_bytes() const;
  double posterior_bytes() const;
  double bytes() const { return table_bytes() + posterior_bytes(); }
  // What the tables depend on (the shape, the scale, the stimuli and the grids, not the prior), as
  // bytes: runs whose keys are equal share one copy of the tables.
  std::string tables_key() const;
};

class QuestPlus {
 public:
  // The definition must be valid (QuestPlusSettings checks it); precomputes the tables.
  explicit QuestPlus(QuestPlusDefinition definition);

  // The stimulus (an index into the domain) with the least expected entropy: the first whose
  // expected entropy is within 1e-12 (relative) of the least, as questplus's first-minimum rule
  // reads on values that may differ from its own by rounding.
  size_t next() const;
  // Every stimulus's expected entropy, nats.
  std::vector<double> expected_entropies() const;
  // Bayes' rule with the answer at `stimulus`: `first_outcome` (correct) or not.
  void update(size_t stimulus, bool first_outcome);
  // The same at a stimulus outside the domain (its likelihoods computed for this answer).
  void update_at(double x, bool first_outcome);

  double entropy() const { return entropy_; }  // of the posterior, nats
  // The joint posterior's mode (the first maximum in the grid's order), and each parameter's
  // marginal mean.
  ParameterPoint mode() const;
  ParameterPoint mean() const;
  // Each parameter's marginal quantile: the least grid value whose cumulative probability reaches
  // `probability`.
  ParameterPoint quantile(double probability) const;
  // The posterior distribution of a function of the parameters: its value at the mode, its mean,
  // and its 2.5 % and 97.5 % quantiles.
  std::array<double, 4> distribution_of(
      const std::function<double(const ParameterPoint&)>& f) const;
  int trials() const { return trials_; }
  // Answers that no parameter point allows, left out of the posterior.
  int impossible_answers() const { return impossible_; }
  const QuestPlusDefinition& definition() const { return definition_; }
  // Whether this run reads the same copy of the tables as `other`: runs of definitions with one
  // tables_key share it while any of them lives (a server holds a run per participant).
  bool shares_tables_with(const QuestPlus& other) const { return tables_ == other.tables_; }

 private:
  // Each parameter's marginal posterior, summed once per answer (on the thread that asks: the
  // study's, never the background choice's).
  const std::array<std::vector<double>, kQuestPlusParameters>& marginals() const;
  double posterior_entropy() const;
  void multiply(const double* psi, bool first_outcome);  // posterior × ψ or 1 − ψ, normalised

  struct Tables {
    std::vector<double> likelihood;       // [stimulus][point]: ψ
    std::vector<double> outcome_entropy;  // [stimulus][point]: −ψ ln ψ − (1 − ψ) ln(1 − ψ)
  };
  static Tables tabulate(const QuestPlusDefinition& d);
  // The tables of `d`: the copy a living run already has, else new ones.
  static std::shared_ptr<const Tables> shared_tables(const QuestPlusDefinition& d);

  QuestPlusDefinition definition_;
  size_t points_ = 0;
  std::shared_ptr<const Tables> tables_;
  std::vector<double> posterior_;
  double entropy_ = 0;
  mutable std::optional<std::array<std::vector<double>, kQuestPlusParameters>> marginals_;
  int trials_ = 0, impossible_ = 0;
};

}  // namespace countershade::procedures
