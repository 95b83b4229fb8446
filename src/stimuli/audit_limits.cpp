#include "stimuli/audit_limits.h"

namespace countershade {

AuditLimits read_audit_limits(const JsonObject& o) {
  AuditLimits limits;
  limits.max_drift = o.number_in("max_drift", limits.max_drift, 0.0, 100.0);
  limits.max_clipped = o.number_in("max_clipped", limits.max_clipped, 0.0, 1.0);
  if (o.has("screen")) {
    JsonObject screen = o.object("screen");
    limits.screen_width = int(screen.integer_in("width", 0, 1, 65536));
    limits.screen_height = int(screen.integer_in("height", 0, 1, 65536));
    limits.gap_px = int(screen.integer_in("gap_px", limits.gap_px, 0, 65536));
    screen.finish();
  }
  o.finish();
  return limits;
}

}  // namespace countershade
