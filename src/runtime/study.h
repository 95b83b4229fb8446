#pragma once
// A study as the adjustment app runs it: the conditions and images taken from a stimulus set's
// manifest, and the procedure configuration (docs/adjustment-study.md). Everything is checked
// here, before any window opens; errors are one line naming the file and the field.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "procedures/adjustment_block.h"

namespace countershade::runtime {

// One condition of the study: a scene × method × σ with its λ grid. Grid index 0 is λ = 0, the
// unenhanced image; λ(i) = lambda_min + i · lambda_step, derived from the index, never accumulated.
struct Condition {
  std::string scene, method;
  double sigma = 0;
  int grid_size = 2;  // indices 0 .. grid_size − 1
};

struct StimulusImage {
  std::filesystem::path file;  // absolute or relative to the working directory
  std::string relative;        // as listed in the manifest
  std::string sha256;
  int width = 0, height = 0;
};

// What one side shows: a still (one image), or a sequence's frames looped at its frame rate.
struct Stimulus {
  std::vector<int> frames;  // indices into Study::images, in frame order
  double fps = 0;           // 0 for a still
  std::string sequence;     // the sequence's folder in the set; empty for a still

  // The frame shown `seconds` into the session: every stimulus loops on the same clock, so both
  // sides stay in step and a λ step keeps the loop's phase.
  int frame_at(double seconds) const;
};

struct Study {
  std::filesystem::path manifest_path;
  std::string manifest_sha256;  // identifies the stimulus set in the responses
  std::string set_name;
  uint64_t manifest_seed = 1;
  int bits =
      8;  // the PNGs' bits per channel: 8, or 16 (shown through a 10-bit framebuffer or dithered)
  double lambda_min = 0, lambda_step = 0.05;
  // The set's screen (manifest `viewing`): its pixels per degree and viewing distance, which the
  // monitor must match.
  std::optional<double> pixels_per_degree, distance_mm;
  std::vector<Condition> conditions;
  // Per condition: slot 0 is the reference (unenhanced) stimulus, slot 1 + i the stimulus of λ
  // index i (indices into `stimuli`).
  std::vector<std::vector<int>> condition_images;
  std::vector<Stimulus> stimuli;
  std::vector<StimulusImage> images;  // every image (frame) the study shows, once each
  procedures::StudyConfig config;     // the adjustment block (the forced-choice app reads its own)
  nlohmann::ordered_json config_source;  // where the configuration came from

  // λ of a grid index, derived from the index and rounded to the decimal grid as the set does.
  double lambda(int index) const;
  // The top of the grid an observer can reach in a condition (the responses' lambda_max).
  double lambda_max(int condition) const {
    return lambda(int(condition_images[size_t(condition)].size()) - 2);
  }
  // The first image of a stimulus.
  const StimulusImage& image_of(int stimulus) const {
    return images[size_t(stimuli[size_t(stimulus)].frames[0])];
  }
  int width(int condition) const { return image_of(condition_images[size_t(condition)][0]).width; }
  int height(int condition) const {
    return image_of(condition_images[size_t(condition)][0]).height;
  }
  int max_width() const;
  int max_height() const;
  // Whether any of a condition's images differs from its reference (a control whose images do
  // not change with λ teaches nothing in practice).
  bool changes_with_lambda(int condition) const;
};

// Loads the manifest and the configuration (`config_file`, else the experiment's "adjust" object,
// else the defaults), and builds the conditions. Throws InputError.
Study load_study(const std::filesystem::path& manifest,
                 const std::optional<std::filesystem::path>& config_file);

// Checks that every image the study shows exists and matches its size and sha256 in the manifest.
// Throws InputError naming the first bad file.
void verify_study_images(const Study& study);

// Subject ids become file names: letters, digits, '-' and '_', at most 64 characters.
void check_subject_id(const std::string& subject);

// The seed of one subject's session: the study seed mixed with the subject id and session number,
// so every subject gets their own reproducible order.
uint64_t session_seed(uint64_t study_seed, const std::string& subject, int session);

}  // namespace countershade::runtime
