#include "audit/bracket_check.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/number_format.h"
#include "observer/prediction_report.h"

namespace countershade {
namespace {

using observer::ConditionPrediction;
using observer::rounded;

bool responds(const ConditionPrediction& c) {
  return std::any_of(c.jnd.begin(), c.jnd.end(), [](double v) { return v > 0; });
}

// The λ at a level, extrapolated linearly from the grid's top where the grid ends below it.
double lambda_at(const ConditionPrediction& c, size_t level) {
  if (c.lambda_at[level]) return *c.lambda_at[level];
  return observer::kPredictionLevels[level] * c.lambda.back() / c.jnd_at_lambda_max();
}

// The largest 1, 2 or 5 × 10^k at most `v`.
double nice_floor(double v) {
  const double decade = std::pow(10.0, std::floor(std::log10(v)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * decade <= v * (1 + 1e-12)) return m * decade;
  return decade;
}

AuditCheck bracket_check(const ConditionPrediction& c, const LambdaGridInfo& grid) {
  AuditCheck check{"the grid brackets the predicted thresholds", c.scene,
                   c.method + " sigma " + format_value(c.sigma), true, ""};
  if (!responds(c)) {
    check.detail = "a control: no predicted response at any λ";
    return check;
  }
  std::ostringstream d;
  const double low = lambda_at(c, 0), high = lambda_at(c, 2);
  const int below =
      int(std::count_if(c.lambda.begin(), c.lambda.end(), [low](double l) { return l < low; })) - 1;
  if (!c.lambda_at[0]) {
    check.passed = false;
    d << "never reaches 1 JND (" << rounded(c.jnd_at_lambda_max()) << " JND at the top, λ "
      << format_value(grid.max) << ")";
  } else if (below < kStepsBelowThreshold) {
    check.passed = false;
    d << "λ at 1 JND " << rounded(low) << " has " << std::max(below, 0)
      << " grid step(s) below it, "
      << "fewer than " << kStepsBelowThreshold;
  } else if (!c.lambda_at[2]) {
    check.passed = false;
    d << "the grid ends at λ " << format_value(grid.max) << " below the λ at 4 JND (about "
      << rounded(high) << ")";
  } else {
    d << "λ at 1 JND " << rounded(low) << " with " << below << " steps below it; λ at 4 JND "
      << rounded(high);
  }
  check.detail = d.str();
  return check;
}

}  // namespace

int SuggestedGrid::count() const { return int(std::floor((max - min) / step + 1e-9)) + 1; }

std::string SuggestedGrid::json() const {
  return "{\"min\": " + format_value(min) + ", \"max\": " + format_value(max) +
         ", \"step\": " + format_value(step) + "}";
}

std::optional<SuggestedGrid> bracketing_grid(const observer::SetPrediction& prediction) {
  double smallest_low = INFINITY, largest_high = 0;
  for (const auto& c : prediction.conditions) {
    if (!responds(c)) continue;
    smallest_low = std::min(smallest_low, lambda_at(c, 0));
    largest_high = std::max(largest_high, lambda_at(c, 2));
  }
  if (!(largest_high > 0)) return std::nullopt;
  SuggestedGrid g;
  g.step = nice_floor(smallest_low / (kStepsBelowThreshold + 1));
  g.max = std::ceil(1.25 * largest_high / g.step - 1e-9) * g.step;
  g.max = std::stod(format_value(round_to(g.max, 12)));
  return g;
}

void add_bracket_checks(AuditReport& report, const observer::SetPrediction& prediction,
                        const LambdaGridInfo& grid, double ppd) {
  std::vector<std::string> short_of;
  for (const auto& c : prediction.conditions) {
    report.checks.push_back(bracket_check(c, grid));
    if (!report.checks.back().passed)
      short_of.push_back(c.scene + " " + report.checks.back().condition);
  }
  std::ostringstream note;
  note << "Bracket check at " << rounded(ppd) << " pixels per degree (countershade predict): ";
  if (short_of.empty()) {
    note << "every condition's grid brackets its predicted thresholds.";
  } else {
    note << short_of.size() << " condition(s) fall short (" << short_of.front()
         << (short_of.size() > 1 ? ", …" : "") << ")";
    if (const auto g = bracketing_grid(prediction))
      note << "; a grid that brackets every condition: \"lambda\": " << g->json() << " ("
           << g->count() << " values"
           << (g->count() > 200 ? "; the thresholds span more than one grid serves well: "
                                  "consider splitting the set"
                                : "")
           << ").";
  }
  report.notes.push_back(note.str());
}

}  // namespace countershade
