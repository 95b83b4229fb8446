#pragma once
// Outputs of an analysis: results.json, CSV tables, SVG figures and a self-contained HTML report.

#include <filesystem>
#include <vector>

#include "analysis/analysis.h"
#include "analysis/forced_choice_analysis.h"

namespace countershade::analysis {

// Writes results.json (one block: the block itself; several: {"methods": [...]}; the keys of
// `extra` added at the top) and, per block, the tables, and (with `figures`) the figures and
// report.html, into `dir`.
void write_outputs(const std::vector<BlockResults>& results, const std::filesystem::path& dir,
                   bool figures,
                   const nlohmann::ordered_json& extra = nlohmann::ordered_json::object());

// Writes the forced-choice results: psychometric_fits.csv and (with `figures`) one
// psychometric-SCENE.svg per scene (the name reduced to letters, digits, '.', '_' and '-'). The
// results.json block is added by the caller. Returns scene → figure file name.
std::vector<std::pair<std::string, std::string>> write_forced_choice_outputs(
    const ForcedChoiceResults& results, const std::filesystem::path& dir, bool figures);

}  // namespace countershade::analysis
