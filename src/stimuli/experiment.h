#pragma once
// The experiment file (versioned JSON, docs/stimulus-sets.md): scenes and their views, methods
// with their σ lists and options, the λ grid, output encoding and a seed. Everything is checked,
// and every scene file loaded, before any rendering starts.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "enhance/method.h"
#include "render/scene.h"

namespace countershade {

inline constexpr int kExperimentFormatVersion = 1;

struct ExperimentScene {
  std::string name;
  std::filesystem::path file;
  std::optional<int> width, height, spp;
};

struct ExperimentMethod {
  std::string method;  // registry name
  std::string label;   // folder name: method, plus the operator for depth-usm
  std::string sigma_key;        // which option the σ list sets (sigma, sigma_fraction, kernel_percent, ...)
  std::vector<double> sigmas;   // one condition each, recorded as "sigma" in the manifest
  MethodOptions options;        // the rest of the options
  int ring_samples = 3;         // usm3d: 1-ring supersampling
  std::vector<std::string> scenes;  // the scenes it applies to (empty: all)
  bool applies_to(const std::string& scene) const;
  MethodOptions for_sigma(double sigma) const;
};

struct LambdaGrid {
  double min = 0, max = 3, step = 0.05;
  int count() const;                 // number of grid values, min and max included
  double value(int index) const;     // λ derived from the index, never accumulated
};

struct Experiment {
  std::filesystem::path file;
  std::string name;
  nlohmann::json content;  // the file as read, recorded in the manifest
  std::string sha256;      // of the file's bytes
  uint64_t seed = 1;
  int bits = 8;
  LambdaGrid lambda;
  std::vector<ExperimentScene> scenes;
  std::vector<ExperimentMethod> methods;
  int contact_columns = 6;
};

Experiment load_experiment(const std::filesystem::path& path);

// The scene as the experiment renders it: view overrides and the experiment's seed applied.
Scene load_experiment_scene(const Experiment& experiment, const ExperimentScene& scene);

// "0.02", "1.25": the shortest text that round-trips a grid value, used in paths and manifests.
std::string format_value(double v);

}  // namespace countershade
