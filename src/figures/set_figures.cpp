#include "figures/set_figures.h"

#include "figures/coherence_figures.h"
#include "figures/congruence_figures.h"
#include "figures/contact_sheet.h"
#include "figures/depth_scale_figures.h"
#include "figures/flicker_figures.h"

namespace countershade {

void write_set_figures(const Experiment& e, const std::filesystem::path& dir,
                       const Manifest& manifest, bool contact_sheets) {
  if (contact_sheets) write_set_contact_sheets(e, dir, manifest);
  if (e.congruence) write_congruence_figures(e, dir, manifest, contact_sheets);
  write_coherence_figures(e, dir, manifest);
  write_flicker_figures(e, dir, manifest);
  write_depth_scale_figures(e, dir, manifest);
}

}  // namespace countershade
