#pragma once
// The study as an exported page holds it (study.js, written by export-web), rebuilt as the
// runtime's Study, so that the engine runs the app's plan and procedures on the same conditions.
// The native tests build it too, to compare the WebAssembly engine with the app.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "adjust/procedure.h"
#include "runtime/study.h"

namespace countershade::web_engine {

// The conditions (scene, method, sigma_value, grid: one entry per λ index) and the λ grid
// ({min, step}). Per condition, "sha256" lists its reference's and each λ image's hash; without
// it every λ image counts as differing from the reference. Throws nlohmann's errors on a missing
// or mistyped field.
runtime::Study study_from_page(const nlohmann::json& page);

// The study seed ("seed", decimal text: it has 64 bits) mixed with a subject and session, as the
// apps do (runtime::session_seed).
uint64_t page_session_seed(const nlohmann::json& page, const std::string& subject, int session);

// A side as the page names it ("left", "right"; anything else: counterbalanced).
procedures::Side side_named(const std::string& name);

// The app's plan of a subject's session for the page's adjustment study: the same trials as
// `adjust` plans for that subject and session. Throws nlohmann's errors on a missing field.
std::vector<adjust::Trial> page_plan(const nlohmann::json& page, const std::string& subject,
                                     int session);

}  // namespace countershade::web_engine
