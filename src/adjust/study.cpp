#include "adjust/study.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include <tbb/parallel_for.h>

#include "core/error.h"
#include "core/file_bytes.h"
#include "core/json_reader.h"
#include "core/random.h"
#include "core/sha256.h"
#include "stimuli/manifest.h"

namespace countershade::adjust {

namespace fs = std::filesystem;

nlohmann::ordered_json StudyConfig::to_json() const {
  nlohmann::ordered_json j;
  j["seed"] = seed ? nlohmann::ordered_json(*seed) : nlohmann::ordered_json("manifest");
  j["repetitions"] = plan.repetitions;
  j["side"] = side_name(plan.side);
  j["start"] = plan.start == StartMode::random ? "random" : "zero";
  j["practice_trials"] = plan.practice_trials;
  auto& c = j["conditions"] = nlohmann::ordered_json::array();
  for (const auto& s : conditions) c.push_back({{"scene", s.scene}, {"method", s.method}, {"sigma", s.sigma}});
  j["repeat"] = {{"delay_ms", timing.repeat_delay_s * 1000}, {"interval_ms", timing.repeat_interval_s * 1000}};
  j["surround"] = surround;
  j["gap_px"] = gap_px;
  j["font_px"] = font_px;
  j["instructions"] = {{"welcome", text.welcome},       {"resume", text.resume},
                       {"practice", text.practice},     {"practice_done", text.practice_done},
                       {"low", text.questions[0]},      {"high", text.questions[1]},
                       {"best", text.questions[2]},     {"keys", text.keys_hint},
                       {"paused", text.paused},         {"finished", text.finished}};
  return j;
}

StudyConfig parse_study_config(const nlohmann::json& value, const std::string& file, const std::string& path) {
  StudyConfig c;
  JsonObject o(value, file, path);
  if (o.has("seed")) c.seed = uint64_t(o.integer_in("seed", 1, 0, 1ll << 53));
  c.plan.repetitions = int(o.integer_in("repetitions", 1, 1, 100));
  std::string side = o.choice("side", "counterbalanced", {"counterbalanced", "left", "right"});
  c.plan.side = side == "left" ? Side::left : side == "right" ? Side::right : Side::counterbalanced;
  c.plan.start = o.choice("start", "random", {"random", "zero"}) == "zero" ? StartMode::zero : StartMode::random;
  c.plan.practice_trials = int(o.integer_in("practice_trials", 0, 0, 100));
  if (o.has("conditions"))
    for (const auto& s : o.objects("conditions")) {
      StudyConfig::Selection sel{s.string("scene"), s.string("method"), s.number("sigma")};
      s.finish();
      c.conditions.push_back(sel);
    }
  if (o.has("repeat")) {
    JsonObject r = o.object("repeat");
    c.timing.repeat_delay_s = r.number_in("delay_ms", 400, 50, 5000) / 1000;
    c.timing.repeat_interval_s = r.number_in("interval_ms", 100, 16, 2000) / 1000;
    r.finish();
  }
  c.surround = int(o.integer_in("surround", 128, 0, 255));
  c.gap_px = int(o.integer_in("gap_px", 48, 0, 4096));
  c.font_px = o.number_in("font_px", 22, 8, 96);
  if (o.has("instructions")) {
    JsonObject t = o.object("instructions");
    auto& x = c.text;
    x.welcome = t.string_or("welcome", x.welcome);
    x.resume = t.string_or("resume", x.resume);
    x.practice = t.string_or("practice", x.practice);
    x.practice_done = t.string_or("practice_done", x.practice_done);
    x.questions[0] = t.string_or("low", x.questions[0]);
    x.questions[1] = t.string_or("high", x.questions[1]);
    x.questions[2] = t.string_or("best", x.questions[2]);
    x.keys_hint = t.string_or("keys", x.keys_hint);
    x.paused = t.string_or("paused", x.paused);
    x.finished = t.string_or("finished", x.finished);
    t.finish();
  }
  o.finish();
  return c;
}

double Study::lambda(int index) const {
  return std::round((lambda_min + double(index) * lambda_step) * 1e9) / 1e9;
}

int Study::max_width() const {
  int w = 0;
  for (size_t c = 0; c < conditions.size(); ++c) w = std::max(w, width(int(c)));
  return w;
}

int Study::max_height() const {
  int h = 0;
  for (size_t c = 0; c < conditions.size(); ++c) h = std::max(h, height(int(c)));
  return h;
}

Study load_study(const fs::path& manifest_path, const std::optional<fs::path>& config_file) {
  Study study;
  study.manifest_path = manifest_path;
  const std::string mfile = manifest_path.string();
  OrderedJson manifest = read_manifest(manifest_path);
  study.manifest_sha256 = sha256_hex(read_file_bytes(manifest_path));
  auto fail = [&](const std::string& field, const std::string& what) { throw_input_error(mfile + ": " + field, what); };
  study.set_name = manifest.value("experiment_name", manifest_path.parent_path().filename().string());
  if (manifest.contains("bits") && manifest["bits"] != 8)
    fail("bits", "the adjustment app shows 8-bit stimuli; this set has " + manifest["bits"].dump() +
                     "-bit images (generate it with \"output\": {\"bits\": 8})");
  if (manifest.contains("seed") && manifest["seed"].is_number_unsigned()) study.manifest_seed = manifest["seed"];
  if (!manifest.contains("lambda_grid") || !manifest["lambda_grid"].is_object()) fail("lambda_grid", "missing");
  const auto& grid = manifest["lambda_grid"];
  for (const char* key : {"min", "step", "count"})
    if (!grid.contains(key) || !grid[key].is_number()) fail(std::string("lambda_grid.") + key, "missing or not a number");
  study.lambda_min = grid["min"];
  study.lambda_step = grid["step"];
  const int count = grid["count"];
  if (!(study.lambda_step > 0) || count < 2) fail("lambda_grid", "needs a positive step and at least two values");

  // Configuration: an explicit file, else the experiment's "adjust" object, else the defaults.
  if (config_file) {
    study.config = parse_study_config(parse_json_file(*config_file), config_file->string(), "");
    study.config_source = {{"file", config_file->string()}};
  } else if (manifest.contains("experiment") && manifest["experiment"].is_object() &&
             manifest["experiment"].contains("adjust")) {
    nlohmann::json adjust = nlohmann::json::parse(manifest["experiment"]["adjust"].dump());
    study.config = parse_study_config(adjust, mfile, "experiment.adjust");
    study.config_source = "experiment.adjust";
  } else {
    study.config_source = "defaults";
  }

  // Group the stimuli into conditions; index 0 (λ = 0) falls back to the scene's reference image.
  const fs::path set_dir = manifest_path.parent_path();
  std::map<std::string, size_t> image_of_file;
  auto add_image = [&](size_t entry) {
    const auto& s = manifest["stimuli"][entry];
    std::string rel = s["file"];
    auto [it, inserted] = image_of_file.emplace(rel, study.images.size());
    if (inserted)
      study.images.push_back({resolve_in_set(set_dir, rel), rel, s["sha256"], s["width"], s["height"]});
    return int(it->second);
  };
  std::map<std::string, size_t> reference_of_scene;
  using Key = std::tuple<std::string, std::string, double>;
  std::map<Key, std::map<int, size_t>> grids;
  std::vector<Key> order;
  for (size_t i = 0; i < manifest["stimuli"].size(); ++i) {
    const auto& s = manifest["stimuli"][i];
    const std::string where = "stimuli[" + std::to_string(i) + "]";
    if (s["method"] == "none") {
      reference_of_scene.emplace(s["scene"], i);
      continue;
    }
    if (!s.contains("lambda_index") || !s["lambda_index"].is_number_integer()) fail(where + ".lambda_index", "missing");
    if (!s.contains("sigma") || !s["sigma"].is_number()) fail(where + ".sigma", "missing");
    std::string method = s.contains("label") && s["label"].is_string() ? s["label"] : s["method"];
    Key key{s["scene"], method, s["sigma"]};
    if (!grids.count(key)) order.push_back(key);
    int index = s["lambda_index"];
    if (index < 0 || index >= count) fail(where + ".lambda_index", "outside the λ grid (0.." + std::to_string(count - 1) + ")");
    if (!grids[key].emplace(index, i).second) fail(where + ".lambda_index", "λ index " + std::to_string(index) + " listed twice");
  }
  const auto& wanted = study.config.conditions;
  for (const auto& sel : wanted)
    if (!grids.count({sel.scene, sel.method, sel.sigma}))
      throw_input_error(config_file ? config_file->string() + ": conditions" : mfile + ": experiment.adjust.conditions",
                        "the set has no condition scene '" + sel.scene + "', method '" + sel.method + "', sigma " +
                            nlohmann::json(sel.sigma).dump());
  for (const auto& key : order) {
    const auto& [scene, method, sigma] = key;
    if (!wanted.empty() && std::none_of(wanted.begin(), wanted.end(), [&](const auto& s) {
          return s.scene == scene && s.method == method && s.sigma == sigma;
        }))
      continue;
    const auto& grid_entries = grids[key];
    std::vector<int> images;
    for (int index = 0; index < count; ++index) {
      auto it = grid_entries.find(index);
      if (it != grid_entries.end()) {
        images.push_back(add_image(it->second));
      } else if (index == 0 && study.lambda(0) == 0 && reference_of_scene.count(scene)) {
        images.push_back(add_image(reference_of_scene[scene]));
      } else {
        fail("stimuli", "condition " + scene + " / " + method + " / sigma " + nlohmann::json(sigma).dump() +
                            " has no image for λ index " + std::to_string(index) + " (the adjustment needs the whole grid)");
      }
    }
    if (!reference_of_scene.count(scene)) fail("stimuli", "scene '" + scene + "' has no reference (method \"none\") image");
    const int reference = add_image(reference_of_scene[scene]);
    const auto& ref = study.images[size_t(reference)];
    for (int img : images)
      if (study.images[size_t(img)].width != ref.width || study.images[size_t(img)].height != ref.height)
        fail("stimuli", "'" + study.images[size_t(img)].relative + "' is not the size of its reference '" + ref.relative + "'");
    // Slot 0 of the condition's list is the reference (the unenhanced side); the grid follows.
    images.insert(images.begin(), reference);
    study.conditions.push_back({scene, method, sigma, count});
    study.condition_images.push_back(std::move(images));
  }
  if (study.conditions.empty()) fail("stimuli", "no condition with a λ grid (the set has only reference images)");
  return study;
}

void verify_study_images(const Study& study) {
  std::vector<std::string> problems(study.images.size());
  tbb::parallel_for(size_t(0), study.images.size(), [&](size_t i) {
    const auto& image = study.images[i];
    std::error_code ec;
    if (!fs::is_regular_file(image.file, ec)) {
      problems[i] = "missing image (listed in the manifest, not in the set folder)";
      return;
    }
    if (sha256_file(image.file) != image.sha256) problems[i] = "sha256 does not match the manifest (the file was changed or is corrupt)";
  });
  for (size_t i = 0; i < problems.size(); ++i)
    if (!problems[i].empty()) throw_input_error(study.images[i].file.string(), problems[i]);
}

void check_subject_id(const std::string& subject) {
  if (subject.empty()) throw_input_error("--subject", "empty subject id");
  if (subject.size() > 64) throw_input_error("--subject", "longer than 64 characters");
  for (char c : subject)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_'))
      throw_input_error("--subject", "'" + subject + "' may only use letters, digits, '-' and '_' (it becomes a file name)");
}

uint64_t session_seed(uint64_t study_seed, const std::string& subject, int session) {
  return hash_combine(hash_combine(study_seed, hash_string(subject)), uint64_t(session));
}

}  // namespace countershade::adjust
