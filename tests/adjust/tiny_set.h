#pragma once
// A small stimulus set for the adjustment tests: two views of the lit cube, usm3d at two σ, and
// by default a six-value λ grid, so a full session is a few seconds.

#include <filesystem>
#include <string>

#include "stimuli/experiment.h"
#include "stimuli/stimulus_set.h"
#include "test_util.h"

namespace countershade::testing {

// Writes the experiment (with `adjust` as its "adjust" object, when given) and generates the
// set into dir/set; returns the manifest's path.
inline std::filesystem::path make_tiny_set(const TempDir& dir, const std::string& adjust = "",
                                           int width = 96, int height = 72, double lambda_step = 0.4) {
  write_file(dir / "cube.json", kLitCubeScene);
  std::string text = R"({
    "version": 1, "name": "tiny", "seed": 5,
    "lambda": {"min": 0, "max": 2, "step": )" + format_value(lambda_step) + R"(},
    "scenes": [{"name": "front", "file": "cube.json", "width": )" + std::to_string(width) + R"(, "height": )" +
                     std::to_string(height) + R"(},
               {"name": "small", "file": "cube.json", "width": 80, "height": 60}],
    "methods": [{"method": "usm3d", "sigma_fraction": [0.03, 0.08]}])" +
                     (adjust.empty() ? std::string() : ",\n    \"adjust\": " + adjust) + "\n}";
  auto experiment_file = write_file(dir / "experiment.json", text);
  GenerateOptions options;
  options.contact_sheets = false;
  generate_stimulus_set(load_experiment(experiment_file), dir / "set", options);
  return dir / "set" / "manifest.json";
}

}  // namespace countershade::testing
