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

#include "core/json_reader.h"
#include "formats/manifest.h"

namespace countershade {

struct AuditLimits {
  double max_drift = 1.0;                          // |mean L*(λ) − mean L*(reference)|, L*
  double max_clipped = 0.01;                       // share of pixels clipped by the enhancement
  std::optional<int> screen_width, screen_height;  // pixels; images shown side by side 1:1
  int gap_px = 48;  // between the two images, as the adjustment app shows them
};

// The experiment file's "audit" block (docs/stimulus-sets.md); throws InputError.
AuditLimits read_audit_limits(const JsonObject& o);

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

// Whether the enhancement clipped a pixel: its codes (three channels) differ from the reference's,
// and a channel sits at 0 or at `top` (full scale) where the reference's does not.
inline bool clipped_by_enhancement(const uint16_t* stimulus, const uint16_t* reference,
                                   uint16_t top) {
  if (stimulus[0] == reference[0] && stimulus[1] == reference[1] && stimulus[2] == reference[2])
    return false;
  bool at_limit = false;
  for (int k = 0; k < 3; ++k)
    at_limit |= (stimulus[k] == 0 || stimulus[k] == top) && stimulus[k] != reference[k];
  return at_limit;
}

// Checks the set's integrity first (every file listed with its size and sha256, nothing
// unlisted): a tampered set is an InputError (exit 2). Then measures every stimulus.
AuditReport audit_stimulus_set(const std::filesystem::path& manifest_path,
                               const AuditOptions& options = {});

}  // namespace countershade
