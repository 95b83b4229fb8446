#pragma once
// A stimulus set as a self-contained static web study (docs/online-study.md): jsPsych and
// countershade's adjustment plugin, the set's images (checked against the manifest first) and
// the study file the plugin plans from, so that a browser runs the app's procedure with the app's
// plan and writes the app's responses rows.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "procedures/choice_block.h"
#include "runtime/study.h"

namespace countershade::adjust {

// The forced-choice study of a set, when the page runs it instead of the adjustment study: the
// experiment's forced_choice block as written (the page's engine reads it as the app does) and as
// read (for the texts).
struct WebChoiceStudy {
  nlohmann::json block;
  procedures::ChoiceConfig config;
};

struct WebExportOptions {
  std::filesystem::path output;
  std::filesystem::path assets;  // holds node_modules/ (jsPsych) and web/ (the plugin)
  std::filesystem::path engine;  // holds countershade-engine.js and .wasm (src/web_engine)
  std::optional<std::string> post_url;
  bool chinrest = false;
  std::string title;
  std::optional<WebChoiceStudy> forced_choice;  // none: the adjustment study
  // The image-computable observer's prediction per condition (observer::model_json), for the
  // page's model observers (?observer=model:SEED); none: the page has none.
  std::optional<nlohmann::json> model;
};

// What the plugin reads (study.js): the set, the plan's inputs, the texts, and per condition its
// λ grid (as the app writes the numbers), image files and their sha256. With a forced-choice
// study, its block and texts instead of the adjustment's.
nlohmann::ordered_json web_study(const runtime::Study& study, const WebExportOptions& options);

// Writes the folder; returns the number of images copied. Throws InputError for a set that
// cannot be exported (missing or altered images, sequences) or missing assets.
size_t export_web_study(const runtime::Study& study, const WebExportOptions& options);

}  // namespace countershade::adjust
