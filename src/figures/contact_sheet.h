#pragma once
// Contact sheets: one PNG per scene and method, a labelled grid of thumbnails (σ rows, for a
// sequence four of its frames per σ, × selected λ columns), so a researcher sees a whole set at a
// glance.

#include <filesystem>
#include <string>
#include <vector>

#include "core/image.h"
#include "formats/manifest.h"
#include "stimuli/experiment.h"

namespace countershade {

struct ContactCell {
  std::filesystem::path file;  // a stimulus PNG
  std::string caption;         // printed under the thumbnail (ASCII); may be empty
};

// cells[r][c] is the stimulus at row label r and column label c.
void write_contact_sheet(const std::filesystem::path& output, const std::string& title,
                         const std::vector<std::string>& row_labels,
                         const std::vector<std::string>& column_labels,
                         const std::vector<std::vector<ContactCell>>& cells,
                         int thumbnail_width = 200);

// The contact sheets of a finished set: one per scene and method, σ rows × evenly spaced λ
// columns (the first and the last included), in DIR/contact-sheets/, each thumbnail captioned
// with its estimated sampling noise (L* RMS). A set that misses an image (a shard) gets none, and a
// condition with one σ and one λ gets none (a sheet of one image).
void write_set_contact_sheets(const Experiment& experiment, const std::filesystem::path& dir,
                              const Manifest& manifest);

}  // namespace countershade
