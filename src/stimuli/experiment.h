#pragma once
// The experiment file (versioned JSON, docs/stimulus-sets.md): scenes and their views, methods
// with their σ lists and options, the λ grid, output encoding and a seed. Everything is checked,
// and every scene file loaded, before any rendering starts.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/number_format.h"
#include "enhance/method.h"
#include "measures/congruence.h"
#include "render/render_request.h"
#include "render/scene.h"
#include "stimuli/screen.h"

namespace countershade {

inline constexpr int kExperimentFormatVersion = 1;

// A light direction relative to the view: elevation above the view's horizon and azimuth from
// the direction towards the viewer (positive to the viewer's right), both in degrees.
// A light direction laid out around the view. `horizon` view: elevation above the view's horizon,
// azimuth from the direction towards the viewer, turning to the viewer's right. `horizon` image:
// elevation above the image plane towards the viewer, azimuth from the view's right, turning up
// (a surface seen head-on, such as a relief from above, is then lit from in front of it at every
// azimuth).
struct ViewLight {
  double elevation = 0, azimuth = 0;
  bool image_plane = false;
};

struct ExperimentScene {
  std::string name;
  std::filesystem::path file;
  std::optional<int> width, height, spp;
  std::optional<ViewLight> light;  // every directional light of the scene points this way
  std::string swept_from;  // with `light`: the name of the scene entry it is one direction of
  // A sequence: frames A … B of the scene's animation, each a stimulus of its own (unset: a still).
  std::optional<std::pair<int, int>> frames;
  double fps = 0;  // the animation's frame rate, for sequences
  // An edge probe ("edge_probe": {"edges_x": [...]}, still scenes): the world x of the stripe
  // edges whose halo widths each stimulus records against depth (stimuli/scale_against_depth.h).
  std::vector<double> probe_edges_x;
  bool is_sequence() const { return frames.has_value(); }
};

struct ExperimentMethod {
  const EnhancementMethod* method = nullptr;
  std::string label;           // folder name: the method's label unless the experiment gives one
  std::string sigma_key;       // the width key the σ list was given under ("" without a width)
  std::vector<double> sigmas;  // one condition each, recorded as "sigma" in the manifest
  std::vector<std::shared_ptr<const MethodParameters>> parameters;  // parsed, one per σ
  RenderRequest request;            // what it needs from rendering, over all its σ
  std::vector<std::string> scenes;  // the scenes it applies to (empty: all)
  bool applies_to(const std::string& scene) const;
};

struct LambdaGrid {
  double min = 0, max = 3, step = 0.05;
  int count() const;              // number of grid values, min and max included
  double value(int index) const;  // λ derived from the index, never accumulated
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
  std::optional<NoiseBudget> noise;      // replaces the scenes' budgets (a scene's spp still wins)
  bool congruence = false;               // score every stimulus (methods.md, "Congruence score")
  CongruenceOptions congruence_options;  // "congruence": {"penalty", "tensor_sigma"}
  // Measure every stimulus's perspective coherence under a camera dolly of this fraction of the
  // eye–target distance (methods.md, "Perspective coherence metric").
  std::optional<double> coherence_dolly;
  bool video = false;  // a lossless video of every sequence (stimuli/sequence_videos.h)
  // Every stimulus gets its reference's mean L* by a uniform offset of its object pixels
  // (stimuli/mean_hold.h): a study-design option on top of the methods.
  bool hold_mean = false;
  // Each still scene's exposure is lowered and its black level raised, for all its stimuli alike,
  // until no condition clips more than `max_clipped` (the audit's limit) at the grid's extremes
  // (stimuli/headroom.h).
  bool headroom = false;
  double max_clipped = 0.01;
  // The screen the study is shown on ("screen"): its pixels per degree turn sizes and σ given in
  // degrees (`width_deg`, `sigma_deg`) into pixels.
  std::optional<Screen> screen;
};

Experiment load_experiment(const std::filesystem::path& path);

// The unit direction towards a light at `light` relative to the camera's view.
glm::dvec3 view_light_direction(const Camera& camera, const ViewLight& light);

// The scene as the experiment renders it: view and light overrides and the experiment's seed
// applied.
Scene load_experiment_scene(const Experiment& experiment, const ExperimentScene& scene);

}  // namespace countershade
