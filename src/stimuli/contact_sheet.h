#pragma once
// Contact sheets: one PNG per scene and method, a labelled grid of thumbnails (σ rows × selected
// λ columns), so a researcher sees a whole set at a glance.

#include <filesystem>
#include <string>
#include <vector>

#include "core/image.h"

namespace countershade {

struct ContactCell {
  std::filesystem::path file;  // a stimulus PNG
};

// rows[r][c] are the stimuli at row label r and column label c.
void write_contact_sheet(const std::filesystem::path& output, const std::string& title,
                         const std::vector<std::string>& row_labels, const std::vector<std::string>& column_labels,
                         const std::vector<std::vector<std::filesystem::path>>& cells, int thumbnail_width = 200);

}  // namespace countershade
