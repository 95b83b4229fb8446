#pragma once
// QUEST (Watson & Pelli 1983) as Psychtoolbox's Quest functions compute it: a gridded posterior
// over the threshold (Gaussian prior around tGuess, truncated to ±range/2), a Weibull
// psychometric function shifted so that the threshold gives pThreshold, and the posterior
// quantile of Pelli's (1987) most informative order as the next intensity. Intensities are in
// the procedure's units (Psychtoolbox uses log10 contrast).

#include <optional>
#include <string>
#include <vector>

#include "core/parameters.h"

namespace countershade::procedures {

struct QuestParameters {
  double t_guess = 0, t_guess_sd = 3;
  double p_threshold = 0.82;
  double beta = 3.5, delta = 0.01, gamma = 0.5;
  double grain = 0.01;
  std::optional<double> range;  // absent: 500 grain steps
};

// Reads QuestCreate's arguments (tGuess, tGuessSd, pThreshold, beta, delta, gamma, grain, range)
// and checks them together.
QuestParameters read_quest_parameters(const ParameterBag& bag);
// Their documentation, with the defaults read_quest_parameters uses.
std::vector<ParameterDoc> quest_parameter_docs();

class Quest {
 public:
  // Throws InputError (naming `where`) when the parameters give no usable psychometric function.
  explicit Quest(const QuestParameters& parameters, const std::string& where = "quest");

  // The posterior quantile of the given order (default: the most informative one), the next
  // intensity to test.
  double quantile() const { return quantile(quantile_order_); }
  double quantile(double order) const;
  double mean() const;
  double mode() const;
  double sd() const;
  void update(double intensity, bool correct);

  const QuestParameters& parameters() const { return p_; }
  int dim() const { return dim_; }
  double x_threshold() const { return x_threshold_; }
  double quantile_order() const { return quantile_order_; }
  // The lowest and highest threshold the posterior can hold.
  double lowest() const { return p_.t_guess + x_.front(); }
  double highest() const { return p_.t_guess + x_.back(); }
  int trials() const { return trials_; }

 private:
  double psychometric(double x) const;  // p2 at offset x from threshold, before the shift
  QuestParameters p_;
  int dim_ = 500;
  double x_threshold_ = 0, quantile_order_ = 0.5;
  std::vector<double> x_, pdf_;  // dim + 1 grid points relative to tGuess
  std::vector<double> p2_;       // 2·dim + 1 values of the shifted psychometric function
  int trials_ = 0;
};

}  // namespace countershade::procedures
