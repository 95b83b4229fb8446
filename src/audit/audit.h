#pragma once
// The stimulus audit: what a reviewer asks of a set before a study runs on it. Per stimulus, the
// mean L*, the RMS contrast (SD of L*), the share of pixels the enhancement clipped, CIEDE2000
// against the scene's reference (mean and 99th percentile), the share of pixels changed and the
// sampling noise the manifest estimates; per condition (scene × method × σ), checks with limits
// from the experiment's "audit" block: λ = 0 equals the reference, mean L* does not drift, little
// is clipped, the noise meets its budget, every λ step changes the image, and the images fit the
// declared screen 1:1.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "formats/manifest.h"
#include "stimuli/audit_limits.h"

namespace countershade {

struct StimulusAudit {
  std::string file, scene, condition;  // condition: "<label> sigma <σ>", empty for references
  std::string sha256;                  // the manifest's checksum, verified before measuring
  double sigma = 0, lambda = 0;
  int frame = -1;  // a sequence's frame; -1 for a still
  bool reference = false;
  double mean_lightness = 0, rms_contrast = 0, clipped_fraction = 0;
  std::optional<double>
      mean_luminance_cd_m2;  // on a calibrated display (its reference records the range)
  double drift = 0;          // mean L* minus its reference's (the same frame's, in a sequence)
  double delta_e_mean = 0, delta_e_p99 = 0, changed_fraction = 0;  // against the reference
  std::optional<double> noise_rms, noise_p99;
  std::optional<bool> noise_met;
  // 16-bit sets: the share of the ideal change (L* against the reference, RMS over the image) that
  // the same stimulus and reference rounded to 8 bits would lose: RMS(ΔL*₈ − ΔL*₁₆) / RMS(ΔL*₁₆).
  // None at 8 bits (no ideal to compare with) and where nothing changes.
  std::optional<double> quantisation_loss;
};

// The λ steps of a condition where more than this share of the change is lost at 8 bits get a note.
inline constexpr double kQuantisationWarning = 0.25;

struct AuditCheck {
  std::string check, scene, condition;  // condition empty: the whole scene or set
  bool passed = true;
  std::string detail;
};

struct AuditReport {
  std::filesystem::path manifest;
  std::string set_name;
  AuditLimits limits;
  std::vector<StimulusAudit> stimuli;  // in manifest order
  std::vector<AuditCheck> checks;
  std::vector<std::string> notes;  // e.g. how L* was decoded

  size_t failed() const;
  std::string summary() const;  // one line: "1224 images, 100 checks, 21 failed (11 mean L* drift,
                                // 10 clipped pixels): ..."
};

struct AuditOptions {
  int threads = 0;  // 0 = all cores
  std::function<void(double)> progress;
};

// The stimuli of one condition (scene × method × σ) in λ order (then frame order), with their
// scene's reference (a sequence's first reference frame).
struct AuditCondition {
  std::string scene, name;
  std::vector<const StimulusAudit*> stimuli;
  const StimulusAudit* reference = nullptr;
};
std::vector<AuditCondition> audit_conditions(const AuditReport& report);

// The checks of measured stimuli against the report's limits, per condition and per set
// (appended to report.checks).
void add_audit_checks(AuditReport& report, const Manifest& manifest);

// Checks the set's integrity first (every file listed with its size and sha256, nothing
// unlisted): a tampered set is an InputError (exit 2). Then measures every stimulus.
AuditReport audit_stimulus_set(const std::filesystem::path& manifest_path,
                               const AuditOptions& options = {});

}  // namespace countershade
