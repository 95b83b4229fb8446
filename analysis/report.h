#pragma once
// Outputs of an analysis: results.json, CSV tables, SVG figures and a self-contained HTML report.

#include <filesystem>
#include <vector>

#include "analysis/analysis.h"

namespace countershade::analysis {

// Writes results.json (one block: the block itself; several: {"methods": [...]}) and, per block,
// the tables, and (with `figures`) the figures and report.html, into `dir`.
void write_outputs(const std::vector<BlockResults>& results, const std::filesystem::path& dir, bool figures);

}  // namespace countershade::analysis
