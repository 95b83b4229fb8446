#include "stimuli/experiment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/file_bytes.h"
#include "core/json_reader.h"
#include "core/sha256.h"
#include "enhance/registry.h"
#include "enhance/view_plan.h"
#include "formats/responses.h"
#include "procedures/adjustment_block.h"
#include "procedures/choice_block.h"
#include "render/camera.h"
#include "render/frame_range.h"
#include "render/scene_loader.h"
#include "stimuli/audit_limits.h"

namespace countershade {

int LambdaGrid::count() const {
  const double steps = std::floor((max - min) / step + 1e-9);
  return steps < double(kMostLambdaValues) ? int(steps) + 1
                                           : kMostLambdaValues + 1;  // no overflow of the int
}

double LambdaGrid::value(int index) const {
  double v = min + double(index) * step;
  return std::round(v / kLambdaResolution) *
         kLambdaResolution;  // exact decimal values: 0.15, not 0.15000000000000002
}

bool ExperimentMethod::applies_to(const std::string& scene) const {
  return scenes.empty() || std::find(scenes.begin(), scenes.end(), scene) != scenes.end();
}

namespace {

// The method's width key that the entry gives a σ list under (exactly one), or "" for a method
// without a width axis.
std::string width_key(const EnhancementMethod& method, const JsonObject& o) {
  std::string found, list;
  int count = 0;
  std::vector<std::string> keys;
  for (const auto& w : method.axes().widths) {
    keys.push_back(w.key);
    if (w.key == "sigma_px") keys.push_back("sigma_deg");  // a σ in pixels may be given in degrees
  }
  for (const auto& key : keys) {
    list += (list.empty() ? "" : ", ") + key;
    if (o.has(key)) {
      found = key;
      ++count;
    }
  }
  if (list.empty()) return "";
  if (count != 1) o.fail("", method.name() + " needs exactly one σ list (" + list + ")");
  return found;
}

void check_label(const JsonObject& o, const std::string& label) {
  if (label.empty() || label == "." || label == ".." ||
      label.find_first_of("/\\") != std::string::npos)
    o.fail("label", "'" + label + "' must be a plain folder name (no '/', '\\', '.' or '..')");
}

// The pixels per degree that a size in degrees (`what`, at `key`) needs.
double degrees_to_pixels(const JsonObject& o, const std::string& key,
                         const std::optional<Screen>& screen) {
  if (!screen)
    o.fail(key,
           "a size in degrees needs the experiment's \"screen\" block (width_mm, width_px, "
           "distance_mm)");
  return screen->pixels_per_degree();
}

ExperimentMethod parse_method(const JsonObject& o, const std::optional<Screen>& screen) {
  ExperimentMethod m;
  m.method = &method_named(o.string("method"), o.file() + ": " + o.key_path("method"));
  const std::string key = width_key(*m.method, o);
  // σ in degrees is parsed as σ in pixels, so that the stimuli equal those given in pixels.
  const double px_per_unit = key == "sigma_deg" ? degrees_to_pixels(o, key, screen) : 1.0;
  const std::string parsed_key = key == "sigma_deg" ? "sigma_px" : key;
  m.sigma_key = key;
  m.sigmas = key.empty() ? std::vector<double>{0.0} : o.numbers(key);
  if (m.sigmas.empty()) o.fail(key, "the σ list is empty");
  if (std::set<double>(m.sigmas.begin(), m.sigmas.end()).size() != m.sigmas.size())
    o.fail(key, "the σ list has duplicates");
  if (o.has("scenes"))
    for (const auto& s : o.raw("scenes")) {
      if (!s.is_string()) o.fail("scenes", "expected a list of scene names");
      m.scenes.push_back(s.get<std::string>());
    }
  const std::set<std::string> own = {"method", "label", "scenes", key};
  for (size_t g = 0; g < m.sigmas.size(); ++g) {
    ParameterBag bag = ParameterBag::from_json(o.value(), o.file(), o.path(), own);
    if (!key.empty())
      bag.set(parsed_key, m.sigmas[g] * px_per_unit,
              o.file() + ": " + o.key_path(key) + "[" + std::to_string(g) + "]");
    m.parameters.push_back(m.method->parse(bag));
    m.request.merge(m.method->request(*m.parameters.back()), o.file() + ": " + o.path());
  }
  m.label = o.has("label") ? o.string("label") : m.method->label(*m.parameters.front());
  check_label(o, m.label);
  return m;  // the method's parser has checked every other key (no o.finish())
}

LambdaGrid read_lambda_grid(const JsonObject& l) {
  LambdaGrid grid;
  grid.min = l.number_or("min", 0.0);
  grid.max = l.number_or("max", 3.0);
  grid.step = l.number_or("step", 0.05);
  if (!(grid.step > 0)) l.fail("step", "must be positive");
  for (const char* key : {"min", "max", "step"})
    if (std::abs(l.number_or(key, 0.0)) > kLargestLambda)
      l.fail(key, "beyond ±1e6 (every method saturates long before)");
  if (grid.max < grid.min) l.fail("max", "the λ range is empty (max < min)");
  if (grid.count() > kMostLambdaValues) l.fail("step", "more than 100000 λ values");
  l.finish();
  return grid;
}

int read_output_bits(const JsonObject& out) {
  const int bits = int(out.integer_or("bits", 8));
  if (bits != 8 && bits != 16) out.fail("bits", "must be 8 or 16");
  out.finish();
  return bits;
}

ExperimentScene parse_scene(const JsonObject& s, const std::filesystem::path& base,
                            const std::optional<Screen>& screen) {
  ExperimentScene scene;
  scene.name = s.string("name");
  if (scene.name.empty() || scene.name.find_first_of("/\\. ") != std::string::npos)
    s.fail("name", "must be a plain name (no '/', '\\\\', '.' or spaces): it becomes a folder");
  std::filesystem::path file = s.string("file");
  scene.file = file.is_absolute() ? file : base / file;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(scene.file, ec))
    s.fail("file", "unknown scene: no such file " + scene.file.string());
  if (s.has("width")) scene.width = int(s.integer_in("width", 0, 1, 16384));
  if (s.has("height")) scene.height = int(s.integer_in("height", 0, 1, 16384));
  for (auto [key, size] :
       {std::pair{"width_deg", &scene.width}, std::pair{"height_deg", &scene.height}}) {
    if (!s.has(key)) continue;
    const std::string pixel_key = std::string(key).substr(0, std::string(key).size() - 4);
    if (s.has(pixel_key)) s.fail(key, "give the size in pixels or in degrees, not both");
    const long long pixels =
        std::llround(s.number_in(key, 0, 1e-3, 360.0) * degrees_to_pixels(s, key, screen));
    if (pixels < 1 || pixels > 16384)
      s.fail(key, "is " + std::to_string(pixels) + " pixels on this screen (1 to 16384)");
    *size = int(pixels);
  }
  if (s.has("spp")) scene.spp = int(s.integer_in("spp", 0, 1, 65536));
  if (s.has("frames")) {  // the scene is read now, so a bad range fails before anything renders
    const Scene animated = load_scene(scene.file);
    scene.frames =
        frame_range(s.string("frames"), animated, 0, s.file() + ": " + s.key_path("frames"));
    scene.fps = animated.animation->fps;
  }
  if (s.has("edge_probe")) {
    const JsonObject probe = s.object("edge_probe");
    scene.probe_edges_x = probe.numbers("edges_x");
    probe.finish();
    if (scene.probe_edges_x.empty() ||
        !std::is_sorted(scene.probe_edges_x.begin(), scene.probe_edges_x.end()) ||
        std::adjacent_find(scene.probe_edges_x.begin(), scene.probe_edges_x.end()) !=
            scene.probe_edges_x.end())
      s.fail("edge_probe", "edges_x must list at least one world x, in increasing order");
    if (scene.frames) s.fail("edge_probe", "applies to still scenes only");
  }
  return scene;
}

// An angle for a folder name: two decimals at most, no trailing zeros, 'p' for the point ("51p43").
std::string degrees_name(double degrees) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", degrees);
  std::string name = text;
  while (name.back() == '0') name.pop_back();
  if (name.back() == '.') name.pop_back();
  std::replace(name.begin(), name.end(), '.', 'p');
  return name == "-0" ? "0" : name;
}

// "light_directions": {"elevations": [degrees…], "azimuths": N, "horizon": "view"|"image"}: one
// scene per (elevation, azimuth), the azimuths 360°/N apart from 0, named NAME-eELEVATION-aAZIMUTH.
std::vector<ExperimentScene> light_variants(const ExperimentScene& scene, const JsonObject& d) {
  std::vector<double> elevations = d.numbers("elevations");
  const int azimuths = int(d.integer_in("azimuths", 1, 1, 360));
  const bool image_plane = d.choice("horizon", "view", {"view", "image"}) == "image";
  d.finish();
  if (elevations.empty()) d.fail("elevations", "needs at least one elevation");
  std::vector<ExperimentScene> out;
  for (double elevation : elevations) {
    if (!(elevation > -90 && elevation < 90))
      d.fail("elevations", "each elevation must lie in (-90, 90) degrees");
    for (int k = 0; k < azimuths; ++k) {
      ExperimentScene variant = scene;
      variant.light = ViewLight{elevation, 360.0 * k / azimuths, image_plane};
      variant.swept_from = scene.name;
      variant.name += "-e" + degrees_name(elevation) + "-a" + degrees_name(variant.light->azimuth);
      out.push_back(variant);
    }
  }
  return out;
}

std::vector<ExperimentScene> parse_scenes(const JsonObject& root, const std::filesystem::path& base,
                                          const std::optional<Screen>& screen) {
  std::vector<ExperimentScene> scenes;
  std::set<std::string> names;
  for (const auto& s : root.objects("scenes")) {
    const ExperimentScene scene = parse_scene(s, base, screen);
    const std::vector<ExperimentScene> variants =
        s.has("light_directions") ? light_variants(scene, s.object("light_directions"))
                                  : std::vector<ExperimentScene>{scene};
    s.finish();
    for (const auto& v : variants) {
      if (!names.insert(v.name).second) s.fail("name", "duplicate scene name '" + v.name + "'");
      scenes.push_back(v);
    }
  }
  return scenes;
}

// The contact sheets' columns and the measures recorded per stimulus (congruence, coherence).
void read_figure_options(const JsonObject& root, Experiment& e) {
  if (root.has("contact_sheet")) {
    const JsonObject c = root.object("contact_sheet");
    e.contact_columns = int(c.integer_in("columns", 6, 2, 32));
    c.finish();
  }
  // "congruence": true, or an object of the score's options (which also turns it on).
  if (root.has("congruence") && root.value().at("congruence").is_object()) {
    const JsonObject c = root.object("congruence");
    e.congruence = true;
    if (c.choice("penalty", "signed", {"signed", "absolute"}) == "absolute")
      e.congruence_options.penalty = CongruencePenalty::absolute;
    e.congruence_options.tensor_sigma = c.number_in("tensor_sigma", 2.0, 0.5, 50.0);
    c.finish();
  } else {
    e.congruence = root.boolean_or("congruence", false);
  }
  e.video = root.boolean_or("video", false);
  if (e.video && e.bits != 8)
    root.fail("video", "the videos are 8-bit: use \"output\": {\"bits\": 8}");
  if (root.has("coherence")) {
    const JsonObject c = root.object("coherence");
    e.coherence_dolly = c.number_in("dolly", 0.02, 1e-4, 0.5);
    c.finish();
  }
}

// The study-design options on top of the methods: "hold_mean", and "headroom" for still scenes
// only (one exposure would have to serve every frame).
void read_design_options(const JsonObject& root, Experiment& e) {
  e.hold_mean = root.boolean_or("hold_mean", false);
  e.headroom = root.boolean_or("headroom", false);
  for (const auto& scene : e.scenes)
    if (e.headroom && scene.is_sequence())
      root.fail("headroom", "applies to still scenes only ('" + scene.name + "' is a sequence)");
}

}  // namespace

Experiment load_experiment(const std::filesystem::path& path) {
  Experiment e;
  e.file = path;
  e.content = parse_json_file(path);
  e.sha256 = sha256_hex(read_file_bytes(path));
  JsonObject root(e.content, path.string(), "");
  long long version = root.integer("version");
  if (version != kExperimentFormatVersion)
    root.fail("version", "unsupported experiment format version " + std::to_string(version));
  e.name = root.string_or("name", path.stem().string());
  if (root.has("description")) root.string("description");
  // The adjustment procedure: parsed now as `adjust` will parse it, so a typo fails here, not
  // in front of the first participant.
  if (root.has("adjust"))
    procedures::parse_study_config(root.raw("adjust"), path.string(), "adjust");
  if (root.has("forced_choice"))
    procedures::parse_choice_config(root.raw("forced_choice"), path.string(), "forced_choice");
  // The audit's limits, checked now; headroom keeps to its clipping limit.
  if (root.has("audit")) e.max_clipped = read_audit_limits(root.object("audit")).max_clipped;
  e.seed = uint64_t(root.integer_in("seed", 1, 0, 1ll << 53));
  if (root.has("lambda")) e.lambda = read_lambda_grid(root.object("lambda"));
  if (root.has("output")) e.bits = read_output_bits(root.object("output"));
  if (root.has("noise")) e.noise = read_noise_budget(root.object("noise"));
  read_figure_options(root, e);
  if (root.has("screen")) e.screen = read_screen(root.object("screen"));
  e.scenes = parse_scenes(root, path.parent_path(), e.screen);
  std::set<std::string> names;
  for (const auto& scene : e.scenes) names.insert(scene.name);
  if (e.scenes.empty()) root.fail("scenes", "an experiment needs at least one scene");
  std::set<std::string> labels;
  for (const auto& m : root.objects("methods")) {
    e.methods.push_back(parse_method(m, e.screen));
    if (!labels.insert(e.methods.back().label).second)
      m.fail("method", "two methods share the folder '" + e.methods.back().label +
                           "' (give one a \"label\")");
  }
  if (e.methods.empty()) root.fail("methods", "an experiment needs at least one method");
  read_design_options(root, e);
  for (const auto& m : e.methods)
    for (const auto& s : m.scenes)
      if (!names.count(s))
        throw_input_error(path.string() + ": methods",
                          "method '" + m.label + "' names an unknown scene '" + s + "'");
  root.finish();
  return e;
}

glm::dvec3 view_light_direction(const Camera& camera, const ViewLight& light) {
  const CameraRays rays(camera);
  const double e = glm::radians(light.elevation), a = glm::radians(light.azimuth);
  // The horizon's direction towards the viewer, and the view's right and up.
  const glm::dvec3 towards_viewer = -rays.forward(), right = rays.right(), up = rays.up();
  if (light.image_plane)
    return glm::normalize(std::cos(e) * (std::cos(a) * right + std::sin(a) * up) +
                          std::sin(e) * towards_viewer);
  const glm::dvec3 horizon = std::cos(a) * towards_viewer + std::sin(a) * right;
  return glm::normalize(std::cos(e) * horizon + std::sin(e) * up);
}

Scene load_experiment_scene(const Experiment& experiment, const ExperimentScene& s) {
  Scene scene = load_scene(s.file);
  if (s.width) scene.camera.width = *s.width;
  if (s.height) scene.camera.height = *s.height;
  if (experiment.noise) {
    scene.settings.noise = *experiment.noise;
    scene.settings.spp.reset();
  }
  if (s.spp) scene.settings.spp = *s.spp;
  if (s.light) {
    if (scene.directional_lights.empty())
      throw_input_error(experiment.file.string() + ": scenes (" + s.name + ")",
                        "light_directions needs a scene with a directional light");
    for (auto& light : scene.directional_lights)
      light.direction = view_light_direction(scene.camera, *s.light);
  }
  if (scene.settings.sampling == SamplingMode::independent && !scene.settings.spp)
    throw_input_error(
        experiment.file.string() + ": scenes (" + s.name + ")",
        "the scene uses the independent sampler, which takes a fixed spp; give the scene an spp");
  scene.settings.seed = experiment.seed;
  return scene;
}

}  // namespace countershade
