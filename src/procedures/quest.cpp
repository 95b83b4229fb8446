#include "procedures/quest.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"

namespace countershade::procedures {
namespace {

// Linear interpolation of y at v on increasing xs (v inside [xs.front(), xs.back()]).
double interpolate(const std::vector<double>& xs, const std::vector<double>& ys, double v) {
  const size_t hi = size_t(std::upper_bound(xs.begin(), xs.end(), v) - xs.begin());
  if (hi == 0) return ys.front();
  if (hi >= xs.size()) return ys.back();
  const size_t lo = hi - 1;
  return ys[lo] + (v - xs[lo]) * (ys[hi] - ys[lo]) / (xs[hi] - xs[lo]);
}

// x·ln x written as x·ln(x + eps), so that 0 gives 0 (Pelli's formula for the quantile order).
double x_log_x(double x) { return x * std::log(x + DBL_EPSILON); }

constexpr double kHuge = std::numeric_limits<double>::max();

void check_quest_parameters(const QuestParameters& q, const ParameterBag& bag) {
  const double top = 1 - q.delta * (1 - q.gamma);  // the function's ceiling
  if (!(q.p_threshold > q.gamma && q.p_threshold < top))
    bag.fail("pThreshold", "must lie strictly between gamma (" + std::to_string(q.gamma) +
                               ") and 1 − delta·(1 − gamma) (" + std::to_string(top) + ")");
  const double steps = q.range ? *q.range / q.grain : 500;
  if (steps > 1e6)
    bag.fail(q.range ? "range" : "grain", "range / grain gives more than 1000000 grid points");
}

}  // namespace

QuestParameters read_quest_parameters(const ParameterBag& bag) {
  QuestParameters q;
  q.t_guess = bag.required_number("tGuess");
  q.t_guess_sd = bag.required_number("tGuessSd");
  if (!(q.t_guess_sd >= 1e-9)) bag.fail("tGuessSd", "must be above 0");
  q.beta = bag.required_number("beta");
  if (!(q.beta >= 1e-9 && q.beta <= 1e6)) bag.fail("beta", "must be in (0, 1e6]");
  q.delta = bag.number_in("delta", 0, 0, 0.999);
  q.gamma = bag.number_in("gamma", 0, 0, 0.999);
  q.p_threshold = bag.required_number("pThreshold");
  q.grain = bag.number_in("grain", 0.01, 1e-9, kHuge);
  if (bag.given("range")) q.range = bag.required_number("range");
  if (q.range && !(*q.range >= 1e-9)) bag.fail("range", "must be above 0");
  check_quest_parameters(q, bag);
  return q;
}

std::vector<ParameterDoc> quest_parameter_docs() {
  return {
      {"tGuess", "", "Prior mean of the threshold (log10 λ), required"},
      {"tGuessSd", "", "Prior standard deviation (log10 units), required"},
      {"pThreshold", "", "Proportion correct the threshold is defined at, required"},
      {"beta", "", "Slope of the Weibull, required"},
      {"delta", "0", "Lapse rate"},
      {"gamma", "0", "Guess rate: 1/n for n alternatives"},
      {"grain", "0.01", "Step of the posterior's grid (log10 units)"},
      {"range", "", "Width of the posterior's grid (null: 500 grain steps)"},
  };
}

double Quest::psychometric(double x) const {
  return p_.delta * p_.gamma +
         (1 - p_.delta) * (1 - (1 - p_.gamma) * std::exp(-std::pow(10.0, p_.beta * x)));
}

Quest::Quest(const QuestParameters& parameters, const std::string& where) : p_(parameters) {
  if (p_.range) dim_ = 2 * int(std::ceil(*p_.range / p_.grain / 2));
  const int half = dim_ / 2;
  for (int i = -half; i <= half; ++i) {
    x_.push_back(i * p_.grain);
    pdf_.push_back(std::exp(-0.5 * std::pow(x_.back() / p_.t_guess_sd, 2)));
  }
  double total = 0;
  for (double v : pdf_) total += v;
  for (double& v : pdf_) v /= total;

  // The threshold offset: where the unshifted function reaches pThreshold, interpolated over its
  // strictly increasing points.
  std::vector<double> ps, xs;
  for (int i = -dim_; i <= dim_; ++i) {
    const double x = i * p_.grain, p = psychometric(x);
    if (i < dim_ && psychometric((i + 1) * p_.grain) != p) {
      ps.push_back(p);
      xs.push_back(x);
    }
  }
  if (ps.size() < 2 || !(p_.p_threshold >= ps.front() && p_.p_threshold <= ps.back()))
    throw_input_error(
        where,
        "pThreshold " + std::to_string(p_.p_threshold) +
            " is outside the psychometric function's range (gamma to 1 − delta·(1 − gamma))");
  x_threshold_ = interpolate(ps, xs, p_.p_threshold);
  for (int i = -dim_; i <= dim_; ++i) p2_.push_back(psychometric(i * p_.grain + x_threshold_));

  const double pl = p2_.front(), ph = p2_.back();
  const double qh = 1 - ph + DBL_EPSILON, ql = 1 - pl + DBL_EPSILON;
  const double pe = x_log_x(ph) - x_log_x(pl) + qh * std::log(qh) - ql * std::log(ql);
  quantile_order_ = (1 / (1 + std::exp(pe / (pl - ph))) - pl) / (ph - pl);
}

// Multiplies the posterior by the likelihood of the answer at each candidate threshold: the
// psychometric function at (intensity − threshold), read from the table by whole grain steps.
void Quest::update(double intensity, bool correct) {
  const double finite = std::clamp(intensity, -1e10, 1e10);
  const long long shift = std::llround((finite - p_.t_guess) / p_.grain);
  const long long columns = 2LL * dim_ + 1, half = dim_ / 2;
  // Column (0-based) of the table for grid point i (−half..half): the table is stored reversed.
  long long first = (dim_ + 1) - half - shift - 1;
  const long long last = first + dim_;
  if (first < 0)
    first = 0;
  else if (last > columns - 1)
    first = columns - 1 - dim_;
  double total = 0;
  for (int j = 0; j <= dim_; ++j) {
    const double p = p2_[size_t(columns - 1 - (first + j))];
    pdf_[size_t(j)] *= correct ? p : 1 - p;
    total += pdf_[size_t(j)];
  }
  for (double& v : pdf_) v /= total;
  ++trials_;
}

double Quest::quantile(double order) const {
  std::vector<double> cumulative(pdf_.size());
  double running = 0;
  for (size_t i = 0; i < pdf_.size(); ++i) cumulative[i] = running += pdf_[i];
  if (order < cumulative.front()) return p_.t_guess + x_.front();
  if (order > cumulative.back()) return p_.t_guess + x_.back();
  std::vector<double> ps, xs;  // the points where the cumulative sum increases
  double previous = -1;
  for (size_t i = 0; i < cumulative.size(); ++i)
    if (cumulative[i] - previous > 0) {
      ps.push_back(cumulative[i]);
      xs.push_back(x_[i]);
      previous = cumulative[i];
    }
  return p_.t_guess + interpolate(ps, xs, order * cumulative.back());
}

double Quest::mean() const {
  double sum = 0, weighted = 0;
  for (size_t i = 0; i < pdf_.size(); ++i) {
    sum += pdf_[i];
    weighted += pdf_[i] * x_[i];
  }
  return p_.t_guess + weighted / sum;
}

double Quest::mode() const {
  return p_.t_guess + x_[size_t(std::max_element(pdf_.begin(), pdf_.end()) - pdf_.begin())];
}

double Quest::sd() const {
  double sum = 0, first = 0, second = 0;
  for (size_t i = 0; i < pdf_.size(); ++i) {
    sum += pdf_[i];
    first += pdf_[i] * x_[i];
    second += pdf_[i] * x_[i] * x_[i];
  }
  return std::sqrt(second / sum - std::pow(first / sum, 2));
}

}  // namespace countershade::procedures
