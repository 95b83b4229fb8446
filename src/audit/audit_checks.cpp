// The audit's checks: each condition (scene × method × σ) against the limits of the
// experiment's "audit" block, and the set against the declared screen.

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "audit/audit.h"
#include "core/number_format.h"

namespace countershade {
namespace {

std::string fixed(double v, int decimals) { return format_value(round_to(v, decimals)); }

// Every λ = 0 image (each frame's, in a sequence) equals its reference; the worst one reported.
AuditCheck lambda_zero_check(const AuditCondition& c) {
  AuditCheck check{"lambda 0 equals reference", c.scene, c.name, true, "no lambda = 0 image"};
  const StimulusAudit* worst = nullptr;
  for (const auto* s : c.stimuli)
    if (s->lambda == 0.0 && (!worst || s->changed_fraction > worst->changed_fraction)) worst = s;
  if (!worst) return check;
  check.passed = worst->changed_fraction == 0.0;
  check.detail = check.passed
                     ? "identical pixels"
                     : fixed(100 * worst->changed_fraction, 3) + " % of pixels differ (max dE " +
                           fixed(worst->delta_e_p99, 2) + " at p99)" +
                           (worst->frame >= 0 ? " in frame " + std::to_string(worst->frame) : "");
  return check;
}

// The smallest λ whose measure passes the limit, as a clause for a failed check: a reader can tell
// whether the λ range a study cares about (around the first visible difference) is affected.
// The stimuli are in λ order.
std::string first_past(const AuditCondition& c, double limit,
                       double (*measure)(const StimulusAudit&)) {
  for (const auto* s : c.stimuli)
    if (measure(*s) > limit) return "; past it from lambda " + format_value(s->lambda);
  return "";
}

double absolute_drift(const StimulusAudit& s) { return std::abs(s.drift); }
double clipped_share(const StimulusAudit& s) { return s.clipped_fraction; }

AuditCheck drift_check(const AuditCondition& c, double limit) {
  AuditCheck check{"mean L* drift", c.scene, c.name, true, ""};
  double worst = 0, at = 0;
  for (const auto* s : c.stimuli) {
    if (std::abs(s->drift) > std::abs(worst)) {
      worst = s->drift;
      at = s->lambda;
    }
  }
  check.passed = std::abs(worst) <= limit;
  check.detail = (worst >= 0 ? "+" : "") + fixed(worst, 2) + " L* at lambda " + format_value(at) +
                 " (limit " + format_value(limit) + first_past(c, limit, absolute_drift) + ")";
  return check;
}

AuditCheck clipping_check(const AuditCondition& c, double limit) {
  AuditCheck check{"clipped pixels", c.scene, c.name, true, ""};
  double worst = 0, at = 0;
  for (const auto* s : c.stimuli)
    if (s->clipped_fraction > worst) {
      worst = s->clipped_fraction;
      at = s->lambda;
    }
  check.passed = worst <= limit;
  check.detail = fixed(100 * worst, 2) + " % at lambda " + format_value(at) + " (limit " +
                 format_value(100 * limit) + " %" + first_past(c, limit, clipped_share) + ")";
  return check;
}

AuditCheck noise_check(const AuditCondition& c) {
  AuditCheck check{"noise within budget", c.scene, c.name, true,
                   "no noise estimate in the manifest"};
  double worst = 0;
  bool any = false;
  for (const auto* s : c.stimuli) {
    if (!s->noise_rms) continue;
    any = true;
    worst = std::max(worst, *s->noise_rms);
    if (s->noise_met && !*s->noise_met) check.passed = false;
  }
  if (any)
    check.detail =
        "largest RMS " + fixed(worst, 2) + " L*" + (check.passed ? "" : ", budget missed");
  return check;
}

// Every step along the λ grid changes the image. A method whose strength saturates (lla, ES and
// radiance scaling clamp theirs to [0, 1]) writes the same image for the rest of the grid: an
// observer would step through identical pictures and could never find the objectionable end. A
// control condition, whose every image is the reference, is left out: there nothing is enhanced.
// The longest run of one image is reported, per frame in a sequence.
AuditCheck lambda_steps_check(const AuditCondition& c) {
  AuditCheck check{"every lambda step changes the image", c.scene, c.name, true,
                   "no two lambdas share an image"};
  const bool control = std::all_of(c.stimuli.begin(), c.stimuli.end(),
                                   [](const StimulusAudit* s) { return s->changed_fraction == 0; });
  if (control) {
    check.detail = "every image equals the reference (a control)";
    return check;
  }
  // Per frame: the run of one image so far, its first stimulus and its length.
  struct Run {
    const StimulusAudit *first = nullptr, *last = nullptr;
    size_t length = 0;
  };
  std::map<int, Run> runs;
  size_t longest = 1;
  for (const auto* s : c.stimuli) {  // in λ order
    Run& run = runs[s->frame];
    const bool repeats = run.last && run.last->lambda != s->lambda && s->sha256 == run.last->sha256;
    run = repeats ? Run{run.first, s, run.length + 1} : Run{s, s, 1};
    if (run.length <= longest) continue;
    longest = run.length;
    check.passed = false;
    check.detail = "the same image from lambda " + format_value(run.first->lambda) + " to " +
                   format_value(s->lambda) + " (" + std::to_string(run.length) + " grid values" +
                   (s->frame >= 0 ? ", frame " + std::to_string(s->frame) : "") +
                   "): the enhancement stops changing";
  }
  return check;
}

// Two images side by side, 1:1, with the app's gap: they must fit the declared screen.
AuditCheck screen_check(const AuditLimits& limits, const Manifest& manifest) {
  AuditCheck check{"fits the screen 1:1", "", "", true, ""};
  int width = 0, height = 0;
  for (const auto& e : manifest.stimuli) {
    width = std::max(width, e.width);
    height = std::max(height, e.height);
  }
  const int needed = 2 * width + limits.gap_px;
  check.passed = needed <= *limits.screen_width && height <= *limits.screen_height;
  check.detail = "two " + std::to_string(width) + "x" + std::to_string(height) + " images and a " +
                 std::to_string(limits.gap_px) + " px gap need " + std::to_string(needed) + "x" +
                 std::to_string(height) + "; the screen is " +
                 std::to_string(*limits.screen_width) + "x" + std::to_string(*limits.screen_height);
  return check;
}

}  // namespace

std::vector<AuditCondition> audit_conditions(const AuditReport& report) {
  std::map<std::string, const StimulusAudit*> references;
  for (const auto& s : report.stimuli)
    if (s.reference) references.emplace(s.scene, &s);  // a sequence: its first frame
  std::vector<AuditCondition> out;
  std::map<std::pair<std::string, std::string>, size_t> index;
  for (const auto& s : report.stimuli) {
    if (s.reference) continue;
    auto [it, inserted] = index.emplace(std::make_pair(s.scene, s.condition), out.size());
    if (inserted) out.push_back({s.scene, s.condition, {}, references[s.scene]});
    out[it->second].stimuli.push_back(&s);
  }
  for (auto& c : out)
    std::sort(c.stimuli.begin(), c.stimuli.end(), [](auto* a, auto* b) {
      return std::tie(a->lambda, a->frame) < std::tie(b->lambda, b->frame);
    });
  return out;
}

void add_audit_checks(AuditReport& report, const Manifest& manifest) {
  for (const AuditCondition& c : audit_conditions(report)) {
    report.checks.push_back(lambda_zero_check(c));
    report.checks.push_back(drift_check(c, report.limits.max_drift));
    report.checks.push_back(clipping_check(c, report.limits.max_clipped));
    report.checks.push_back(noise_check(c));
    report.checks.push_back(lambda_steps_check(c));
  }
  if (report.limits.screen_width) report.checks.push_back(screen_check(report.limits, manifest));
}

}  // namespace countershade
