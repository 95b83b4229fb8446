#include "runtime/study.h"

// Reads a study from a set's manifest and its adjust block, and checks its images.

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include "core/error.h"
#include "core/file_bytes.h"
#include "core/json_reader.h"
#include "core/random.h"
#include "core/sha256.h"
#include "formats/manifest.h"

namespace countershade::runtime {

namespace fs = std::filesystem;

namespace {

// The λ grid and the seed the study takes from the set.
void read_grid(Study& study, const Manifest& manifest, const std::string& mfile) {
  auto fail = [&](const std::string& field, const std::string& what) {
    throw_input_error(mfile + ": " + field, what);
  };
  if (manifest.bits != 8 && manifest.bits != 16)
    fail("bits", "the apps show 8- or 16-bit PNG stimuli; this set has " +
                     std::to_string(manifest.bits) +
                     "-bit images (generate it with \"output\": {\"bits\": 8} or 16)");
  study.bits = manifest.bits;
  study.manifest_seed = manifest.seed;
  if (manifest.viewing.pixels_per_degree) {
    study.pixels_per_degree = manifest.viewing.pixels_per_degree;
    study.distance_mm = manifest.viewing.distance_mm;
  }
  study.lambda_min = manifest.lambda_grid.min;
  study.lambda_step = manifest.lambda_grid.step;
  if (!(study.lambda_step > 0) || manifest.lambda_grid.count < 2)
    fail("lambda_grid", "needs a positive step and at least two values");
}

// An explicit file, else the experiment's "adjust" object, else the defaults.
void read_config(Study& study, const Manifest& manifest, const std::string& mfile,
                 const std::optional<fs::path>& config_file) {
  if (config_file) {
    study.config =
        procedures::parse_study_config(parse_json_file(*config_file), config_file->string(), "");
    study.config_source = {{"file", config_file->string()}};
  } else if (manifest.experiment.is_object() && manifest.experiment.contains("adjust")) {
    nlohmann::json adjust = nlohmann::json::parse(manifest.experiment["adjust"].dump());
    study.config = procedures::parse_study_config(adjust, mfile, "experiment.adjust");
    study.config_source = "experiment.adjust";
  } else {
    study.config_source = "defaults";
  }
}

using ConditionKey = std::tuple<std::string, std::string, double>;

// The entries of one stimulus: a still's one, or a sequence's frames.
using Entries = std::vector<size_t>;

// The set's conditions in manifest order, each with its entries by λ index, and the reference
// entries of each scene.
struct SetIndex {
  std::map<ConditionKey, std::map<int, Entries>> grids;
  std::vector<ConditionKey> order;
  std::map<std::string, Entries> reference_of_scene;
};

SetIndex index_set(const Manifest& manifest, const std::string& mfile) {
  auto fail = [&](const std::string& field, const std::string& what) {
    throw_input_error(mfile + ": " + field, what);
  };
  const int count = manifest.lambda_grid.count;
  SetIndex index;
  for (size_t i = 0; i < manifest.stimuli.size(); ++i) {
    const ManifestEntry& s = manifest.stimuli[i];
    const std::string where = "stimuli[" + std::to_string(i) + "]";
    if (s.is_reference()) {
      index.reference_of_scene[s.scene].push_back(i);
      continue;
    }
    if (!s.sigma) fail(where + ".sigma", "missing");
    ConditionKey key{s.scene, s.condition_method(), *s.sigma};
    if (!index.grids.count(key)) index.order.push_back(key);
    if (s.lambda_index >= count)
      fail(where + ".lambda_index", "outside the λ grid (0.." + std::to_string(count - 1) + ")");
    Entries& entries = index.grids[key][s.lambda_index];
    if (!entries.empty() && !s.frame)  // only a sequence has several entries per λ
      fail(where + ".lambda_index", "λ index " + std::to_string(s.lambda_index) + " listed twice");
    entries.push_back(i);
  }
  return index;
}

bool selected(const std::vector<procedures::StudyConfig::Selection>& wanted,
              const ConditionKey& key) {
  return wanted.empty() || std::any_of(wanted.begin(), wanted.end(), [&](const auto& s) {
           return s.names(std::get<0>(key), std::get<1>(key), std::get<2>(key));
         });
}

class StudyBuilder {
 public:
  StudyBuilder(Study& study, const Manifest& manifest, std::string mfile)
      : study_(study), manifest_(manifest), mfile_(std::move(mfile)) {}

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw_input_error(mfile_ + ": " + field, what);
  }

  // A stimulus from its entries (frames ordered by their index), once per first file.
  int add_stimulus(Entries entries) {
    const auto frame = [&](size_t e) {
      return manifest_.stimuli[e].frame ? manifest_.stimuli[e].frame->index : 0;
    };
    std::sort(entries.begin(), entries.end(),
              [&](size_t a, size_t b) { return frame(a) < frame(b); });
    for (size_t k = 1; k < entries.size(); ++k)
      if (frame(entries[k]) == frame(entries[k - 1]))
        fail("stimuli[" + std::to_string(entries[k]) + "].frame",
             "frame " + std::to_string(frame(entries[k])) + " of '" +
                 manifest_.stimuli[entries[k]].file + "' is listed twice");
    const ManifestEntry& head = manifest_.stimuli[entries[0]];
    auto [it, inserted] = stimulus_of_file_.emplace(head.file, study_.stimuli.size());
    if (!inserted) return int(it->second);
    Stimulus stimulus;
    for (size_t e : entries) stimulus.frames.push_back(add_image(e));
    if (head.frame) {
      stimulus.fps = head.frame->fps;
      stimulus.sequence = head.sequence();
    }
    study_.stimuli.push_back(std::move(stimulus));
    return int(it->second);
  }

  int add_image(size_t entry) {
    const ManifestEntry& s = manifest_.stimuli[entry];
    auto [it, inserted] = image_of_file_.emplace(s.file, study_.images.size());
    if (inserted)
      study_.images.push_back({resolve_in_set(study_.manifest_path.parent_path(), s.file), s.file,
                               s.sha256, s.width, s.height});
    return int(it->second);
  }

  // Slot 0 is the reference (the unenhanced side), then one image per λ index; index 0 (λ = 0)
  // falls back to the scene's reference image.
  void add_condition(const ConditionKey& key, const SetIndex& index) {
    const auto& [scene, method, sigma] = key;
    const int count = manifest_.lambda_grid.count;
    const auto& entries = index.grids.at(key);
    auto reference = index.reference_of_scene.find(scene);
    if (reference == index.reference_of_scene.end())
      fail("stimuli",
           "scene '" + scene + "' has no reference (method \"" + kReferenceMethod + "\") image");
    std::vector<int> images;
    for (int i = 0; i < count; ++i) {
      auto it = entries.find(i);
      if (it != entries.end())
        images.push_back(add_stimulus(it->second));
      else if (i == 0 && study_.lambda(0) == 0)
        images.push_back(add_stimulus(reference->second));
      else
        fail("stimuli", "condition " + scene + " / " + method + " / sigma " +
                            nlohmann::json(sigma).dump() + " has no image for λ index " +
                            std::to_string(i) + " (the adjustment needs the whole grid)");
    }
    const int ref = add_stimulus(reference->second);
    for (int img : images) check_same_shape(img, ref);
    images.insert(images.begin(), ref);
    study_.conditions.push_back({scene, method, sigma, count});
    study_.condition_images.push_back(std::move(images));
  }

 private:
  void check_same_shape(int stimulus, int ref) const {
    const auto& a = study_.image_of(stimulus);
    const auto& b = study_.image_of(ref);
    if (a.width != b.width || a.height != b.height)
      fail("stimuli", "'" + a.relative + "' is not the size of its reference '" + b.relative + "'");
    const size_t frames = study_.stimuli[size_t(stimulus)].frames.size(),
                 expected = study_.stimuli[size_t(ref)].frames.size();
    if (frames != expected)
      fail("stimuli", "the sequence of '" + a.relative + "' has " + std::to_string(frames) +
                          " frames, its reference " + std::to_string(expected) +
                          " (the two sides play in step)");
  }

  Study& study_;
  const Manifest& manifest_;
  std::string mfile_;
  std::map<std::string, size_t> image_of_file_, stimulus_of_file_;
};

// The named practice conditions, or every condition whose images change with λ.
void choose_practice_conditions(Study& study, const std::string& where) {
  auto& chosen = study.config.plan.practice_conditions;
  const auto& named = study.config.practice_conditions;
  for (size_t n = 0; n < named.size(); ++n) {
    const auto it =
        std::find_if(study.conditions.begin(), study.conditions.end(), [&](const Condition& c) {
          return c.scene == named[n].scene && c.method == named[n].method &&
                 c.sigma == named[n].sigma;
        });
    if (it == study.conditions.end())
      throw_input_error(where + "practice_conditions[" + std::to_string(n) + "]",
                        "not a condition of this study");
    chosen.push_back(int(it - study.conditions.begin()));
  }
  for (int c = 0; named.empty() && c < int(study.conditions.size()); ++c)
    if (study.changes_with_lambda(c)) chosen.push_back(c);
  if (chosen.empty() && study.config.plan.practice_trials > 0)
    throw_input_error(
        where + "practice_trials",
        "no condition's images change with λ, so practice would show nothing to adjust");
}

}  // namespace

Study load_study(const fs::path& manifest_path, const std::optional<fs::path>& config_file) {
  Study study;
  study.manifest_path = manifest_path;
  const std::string mfile = manifest_path.string();
  const Manifest manifest = read_manifest(manifest_path);
  study.manifest_sha256 = manifest.file_sha256;
  study.set_name = manifest.experiment_name;
  read_grid(study, manifest, mfile);
  read_config(study, manifest, mfile, config_file);

  const SetIndex index = index_set(manifest, mfile);
  for (const auto& sel : study.config.conditions)
    if (!index.grids.count({sel.scene, sel.method, sel.sigma}))
      throw_input_error(config_file ? config_file->string() + ": conditions"
                                    : mfile + ": experiment.adjust.conditions",
                        "the set has no condition scene '" + sel.scene + "', method '" +
                            sel.method + "', sigma " + nlohmann::json(sel.sigma).dump());
  StudyBuilder builder(study, manifest, mfile);
  for (const auto& key : index.order)
    if (selected(study.config.conditions, key)) builder.add_condition(key, index);
  if (study.conditions.empty())
    builder.fail("stimuli", "no condition with a λ grid (the set has only reference images)");
  choose_practice_conditions(
      study, config_file ? config_file->string() + ": " : mfile + ": experiment.adjust.");
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
    if (sha256_file(image.file) != image.sha256)
      problems[i] = "sha256 does not match the manifest (the file was changed or is corrupt)";
  });
  for (size_t i = 0; i < problems.size(); ++i)
    if (!problems[i].empty()) throw_input_error(study.images[i].file.string(), problems[i]);
}

}  // namespace countershade::runtime
