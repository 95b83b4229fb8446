#include "adjust/web_export.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/file_bytes.h"
#include "core/image.h"
#include "core/number_format.h"
#include "core/version.h"

namespace countershade::adjust {

// From the study runtime (src/runtime) and the adjustment block (src/procedures).
using procedures::Instructions;
using procedures::StudyConfig;
using runtime::Condition;
using runtime::Stimulus;
using runtime::Study;
using runtime::verify_study_images;

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

namespace {

// The files a study folder takes from the source tree: (from, to).
const std::vector<std::pair<std::string, std::string>> kAssets = {
    {"node_modules/jspsych/dist/index.browser.min.js", "jspsych/jspsych.js"},
    {"node_modules/jspsych/css/jspsych.css", "jspsych/jspsych.css"},
    {"node_modules/@jspsych/plugin-browser-check/dist/index.browser.min.js",
     "jspsych/plugin-browser-check.js"},
    {"node_modules/@jspsych/plugin-virtual-chinrest/dist/index.browser.min.js",
     "jspsych/plugin-virtual-chinrest.js"},
    {"web/deep-images.js", "countershade/deep-images.js"},
    {"web/engine.js", "countershade/engine.js"},
    {"web/layout.js", "countershade/layout.js"},
    {"web/plugin-choice.js", "countershade/plugin-choice.js"},
    {"web/session-plugin.js", "countershade/session-plugin.js"},
    {"web/store.js", "countershade/store.js"},
    {"web/plugin-adjust.js", "countershade/plugin-adjust.js"},
    {"web/main.js", "countershade/main.js"},
    {"web/index.html", "index.html"},
};

// The study logic as WebAssembly (src/web_engine), beside index.html, where the page loads it.
const char* const kEngineFiles[] = {"countershade-engine.js", "countershade-engine.wasm"};

// A 16-bit set's images go to the page as their codes (.rgb16: width × height × RGB, 16-bit
// little-endian, top row first), which WebGL2 takes as an integer texture: a browser decodes a
// 16-bit PNG to 8 bits.
std::string image_name(size_t image, int bits) {
  char name[32];
  std::snprintf(name, sizeof name, "images/%05zu.%s", image + 1, bits == 16 ? "rgb16" : "png");
  return name;
}

std::string rgb16_codes(const fs::path& png) {
  const Image image = read_image(png);
  std::string out;
  out.reserve(size_t(image.width) * size_t(image.height) * 6);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const long code = std::lround(image.at(x, y, std::min(c, image.channels - 1)) * 65535.0f);
        out.push_back(char(code & 0xff));
        out.push_back(char(code >> 8));
      }
  return out;
}

json condition_json(const Study& study, int c) {
  const Condition& condition = study.conditions[size_t(c)];
  const auto& stimuli = study.condition_images[size_t(c)];
  auto image_of = [&](int stimulus) {
    return image_name(size_t(study.stimuli[size_t(stimulus)].frames[0]), study.bits);
  };
  json grid = json::array(), values = json::array(), images = json::array();
  json hashes = json::array({study.image_of(stimuli[0]).sha256});
  for (size_t k = 1; k < stimuli.size(); ++k) {
    grid.push_back(format_value(study.lambda(int(k) - 1)));  // as the app writes it
    values.push_back(study.lambda(int(k) - 1));              // as the app computes with it
    images.push_back(image_of(stimuli[k]));
    hashes.push_back(study.image_of(stimuli[k]).sha256);  // which images change with λ
  }
  return {{"scene", condition.scene},
          {"method", condition.method},
          {"sigma", format_value(condition.sigma)},
          {"sigma_value", condition.sigma},
          {"grid", grid},
          {"grid_values", values},
          {"lambda_max", format_value(study.lambda_max(c))},
          {"reference", image_of(stimuli[0])},
          {"images", images},
          {"sha256", hashes},
          {"width", study.width(c)},
          {"height", study.height(c)}};
}

json texts_json(const Instructions& t) {
  return {{"welcome", t.welcome},
          {"resume", t.resume},
          {"practice", t.practice},
          {"practice_done", t.practice_done},
          {"questions", {t.questions[0], t.questions[1], t.questions[2]}},
          {"keys_hint", t.keys_hint},
          {"paused", t.paused},
          {"finished", t.finished}};
}

void check_exportable(const Study& study) {
  for (const Stimulus& s : study.stimuli)
    if (s.fps > 0)
      throw_input_error(study.manifest_path.string(),
                        "a set of sequences cannot be exported for the web yet (stills only)");
  verify_study_images(study);
}

// The forced-choice study's part: its block and the app's texts for it.
json choice_json(const WebChoiceStudy& choice) {
  const procedures::ChoiceConfig& c = choice.config;
  return {{"block", choice.block},
          {"n_afc", c.n_afc},
          {"layout", procedures::layout_name(c.layout)},
          {"interval_frames", c.interval_frames},
          {"blank_frames", c.blank_frames},
          {"feedback_frames", c.feedback_frames},
          {"texts",
           {{"welcome", c.welcome_text()},
            {"question", c.question},
            {"answer_keys", c.answer_keys()}}}};
}

}  // namespace

json web_study(const Study& study, const WebExportOptions& o) {
  const StudyConfig& c = study.config;
  json conditions = json::array();
  for (size_t i = 0; i < study.conditions.size(); ++i)
    conditions.push_back(condition_json(study, int(i)));
  json out = {
      {"format", "countershade-web-study"},
      {"study", o.forced_choice ? "forced_choice" : "adjust"},
      {"title", o.title.empty() ? study.set_name : o.title},
      {"set", {{"name", study.set_name}, {"sha256", study.manifest_sha256}}},
      {"app_version", kVersion},
      {"seed", std::to_string(c.seed.value_or(
                   study.manifest_seed))},  // a string: JavaScript numbers hold 53 bits
      {"repetitions", c.plan.repetitions},
      {"side", side_name(c.plan.side)},
      {"start", c.plan.start == procedures::StartMode::zero ? "zero" : "random"},
      {"practice_trials", c.plan.practice_trials},
      {"practice_conditions", c.plan.practice_conditions},
      {"timing", {{"delay", c.timing.repeat_delay_s}, {"interval", c.timing.repeat_interval_s}}},
      {"surround", c.surround},
      {"gap_px", c.gap_px},
      {"font_px", c.font_px},
      {"texts", texts_json(c.text)},
      {"lambda_step", format_value(study.lambda_step)},
      {"bits", study.bits},
      // The grid as the app computes λ from an index (runtime::Study::lambda), for the engine.
      {"lambda_grid", {{"min", study.lambda_min}, {"step", study.lambda_step}}},
      {"conditions", conditions},
      {"post_url", o.post_url ? json(*o.post_url) : json(nullptr)},
      {"chinrest", o.chinrest}};
  if (o.model) out["model"] = *o.model;
  if (o.forced_choice) {
    out["seed"] = std::to_string(study.manifest_seed);  // the block's own seed comes first
    out["forced_choice"] = o.forced_choice->block;
    out["choice"] = choice_json(*o.forced_choice);
  }
  return out;
}

size_t export_web_study(const Study& study, const WebExportOptions& o) {
  check_exportable(study);
  for (const auto& [from, to] : kAssets)
    if (!fs::is_regular_file(o.assets / from))
      throw_input_error((o.assets / from).string(),
                        "missing (run `npm ci` in the source tree, see docs/online-study.md)");
  for (const char* file : kEngineFiles)
    if (!fs::is_regular_file(o.engine / file))
      throw_input_error((o.engine / file).string(),
                        "missing (build the WebAssembly engine with scripts/build)");
  std::error_code ec;
  fs::create_directories(o.output / "images", ec);
  if (ec) throw_input_error(o.output.string(), "cannot create the folder");
  for (const auto& [from, to] : kAssets) {
    fs::create_directories((o.output / to).parent_path(), ec);
    write_text_atomically(o.output / to, read_file_bytes(o.assets / from));
  }
  for (const char* file : kEngineFiles)
    write_text_atomically(o.output / file, read_file_bytes(o.engine / file));
  for (size_t i = 0; i < study.images.size(); ++i)
    write_text_atomically(o.output / image_name(i, study.bits),
                          study.bits == 16 ? rgb16_codes(study.images[i].file)
                                           : read_file_bytes(study.images[i].file));
  // A JavaScript file rather than JSON, so the page also opens where fetch() is not allowed;
  // ASCII-only, so no text from the set can end the literal.
  write_text_atomically(o.output / "study.js", "window.COUNTERSHADE_STUDY = " +
                                                   web_study(study, o).dump(1, ' ', true) + ";\n");
  return study.images.size();
}

}  // namespace countershade::adjust
