#pragma once
// Small stimulus sets for the adjustment tests: two views of the lit cube, usm3d at two σ, and
// by default a six-value λ grid, so a full session is a few seconds; and a set of sequences.

#include <filesystem>
#include <string>

#include "stimuli/experiment.h"
#include "stimuli/stimulus_set.h"
#include "test_util.h"

namespace countershade::testing {

// make_tiny_set on the scene already written to dir/cube.json.
inline std::filesystem::path make_tiny_set_of(const TempDir& dir, const std::string& extra = "",
                                              const std::string& adjust = "", int width = 96,
                                              int height = 72, double lambda_step = 0.4) {
  std::string text = R"({
    "version": 1, "name": "tiny", "seed": 5, )" +
                     extra + R"(
    "lambda": {"min": 0, "max": 2, "step": )" +
                     format_value(lambda_step) + R"(},
    "scenes": [{"name": "front", "file": "cube.json", "width": )" +
                     std::to_string(width) + R"(, "height": )" + std::to_string(height) + R"(},
               {"name": "small", "file": "cube.json", "width": 80, "height": 60}],
    "methods": [{"method": "usm3d", "sigma_fraction": [0.03, 0.08]}])" +
                     (adjust.empty() ? std::string() : ",\n    \"adjust\": " + adjust) + "\n}";
  auto experiment_file = write_file(dir / "experiment.json", text);
  GenerateOptions options;
  generate_stimulus_set(load_experiment(experiment_file), dir / "set", options);
  return dir / "set" / "manifest.json";
}

// Writes the lit cube scene and the experiment (with `adjust` as its "adjust" object, when given)
// and generates the set into dir/set; returns the manifest's path. `extra`: more top-level keys
// of the experiment, each followed by a comma.
inline std::filesystem::path make_tiny_set(const TempDir& dir, const std::string& adjust = "",
                                           int width = 96, int height = 72,
                                           double lambda_step = 0.4,
                                           const std::string& extra = "") {
  write_file(dir / "cube.json", kLitCubeScene);
  return make_tiny_set_of(dir, extra, adjust, width, height, lambda_step);
}

// A set of sequences for the playback tests: the orbiting box, all 4 frames at the given size,
// usm2d at one σ over λ ∈ {0, 1}, so each condition is a reference and two sequences.
inline std::filesystem::path make_sequence_set(const TempDir& dir, const std::string& adjust = "",
                                               int width = 64, int height = 48) {
  write_file(dir / "orbit.json", kOrbitingBoxScene);
  const std::string text =
      R"({
    "version": 1, "name": "sequences", "seed": 7,
    "lambda": {"min": 0, "max": 1, "step": 1},
    "scenes": [{"name": "orbit", "file": "orbit.json", "frames": "all", "spp": 1, "width": )" +
      std::to_string(width) + R"(, "height": )" + std::to_string(height) + R"(}],
    "methods": [{"method": "usm2d", "sigma_percent": [2]}])" +
      (adjust.empty() ? std::string() : ",\n    \"adjust\": " + adjust) + "\n}";
  GenerateOptions options;
  generate_stimulus_set(load_experiment(write_file(dir / "experiment.json", text)), dir / "set",
                        options);
  return dir / "set" / "manifest.json";
}

}  // namespace countershade::testing
