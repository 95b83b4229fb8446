#pragma once
// The limits a set's audit checks against, and what counts as a clipped pixel, from the experiment
// file's "audit" block. They belong to the experiment: generation keeps to the clipping limit when
// it finds a scene's headroom, and the audit (src/audit) checks every limit on the finished set.

#include <cstdint>
#include <optional>

#include "core/json_reader.h"

namespace countershade {

struct AuditLimits {
  double max_drift = 1.0;                          // |mean L*(λ) − mean L*(reference)|, L*
  double max_clipped = 0.01;                       // share of pixels clipped by the enhancement
  std::optional<int> screen_width, screen_height;  // pixels; images shown side by side 1:1
  int gap_px = 48;  // between the two images, as the adjustment app shows them
};

// The experiment file's "audit" block (docs/stimulus-sets.md); throws InputError.
AuditLimits read_audit_limits(const JsonObject& o);

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

}  // namespace countershade
