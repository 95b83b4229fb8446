#include "stimuli/experiment.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/file_bytes.h"
#include "core/json_reader.h"
#include "core/sha256.h"

namespace countershade {

std::string format_value(double v) {
  if (std::abs(v) < 1e-12) v = 0;
  char buffer[32];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof buffer, "%.*g", precision, v);
    if (std::abs(std::strtod(buffer, nullptr) - v) <= 1e-12 * std::max(1.0, std::abs(v))) break;
  }
  return buffer;
}

int LambdaGrid::count() const { return int(std::floor((max - min) / step + 1e-9)) + 1; }

double LambdaGrid::value(int index) const {
  double v = min + double(index) * step;
  return std::round(v * 1e9) / 1e9;  // exact decimal grid values (0.15, not 0.15000000000000002)
}

bool ExperimentMethod::applies_to(const std::string& scene) const {
  return scenes.empty() || std::find(scenes.begin(), scenes.end(), scene) != scenes.end();
}

MethodOptions ExperimentMethod::for_sigma(double sigma) const {
  MethodOptions o = options;
  if (sigma_key == "sigma") o.sigma = sigma;
  else if (sigma_key == "sigma_fraction") o.sigma_fraction = sigma;
  else if (sigma_key == "iterations") o.iterations = int(std::lround(sigma));
  else if (sigma_key == "kernel_percent") o.kernel_percent = sigma;
  else if (sigma_key == "sigma_px") o.sigma_px = sigma;
  else if (sigma_key == "sigma_percent") o.sigma_percent = sigma;
  return o;
}

namespace {

const std::vector<std::string> kUsm3dKeys = {"sigma", "sigma_fraction", "iterations"};
const std::vector<std::string> kImageKeys = {"kernel_percent", "sigma_px", "sigma_percent"};
const std::vector<std::string> kCornsweetKeys = {"sigma_px", "sigma"};

ExperimentMethod parse_method(const JsonObject& o) {
  ExperimentMethod m;
  m.method = o.choice("method", "", method_names());
  const EnhancementMethod* method = find_method(m.method);
  m.label = m.method;
  const auto& keys = m.method == "usm3d" ? kUsm3dKeys : m.method == "cornsweet" ? kCornsweetKeys : kImageKeys;
  int found = 0;
  for (const auto& k : keys)
    if (o.has(k)) {
      m.sigma_key = k;
      m.sigmas = o.numbers(k);
      ++found;
    }
  if (m.method == "none") {
    m.sigmas = {0.0};
    m.sigma_key = "none";
  } else {
    std::string list;
    for (const auto& k : keys) list += (list.empty() ? "" : ", ") + k;
    if (found != 1) o.fail("", "give exactly one σ list (" + list + ")");
    if (m.sigmas.empty()) o.fail(m.sigma_key, "the σ list is empty");
    std::set<double> unique(m.sigmas.begin(), m.sigmas.end());
    if (unique.size() != m.sigmas.size()) o.fail(m.sigma_key, "the σ list has duplicates");
  }
  if (m.method == "usm3d") {
    m.options.adapt = o.boolean_or("adapt", true);
    m.ring_samples = int(o.integer_in("ring_samples", 3, 0, 64));
  }
  if (m.method == "depth-usm") {
    m.options.op = o.choice("operator", "darken", {"add", "contrast", "darken", "color"});
    m.options.contrast = o.choice("contrast", "stretch", {"stretch", "equalize", "local"});
    m.options.depth_mapping = o.choice("depth_mapping", "linear", {"linear", "zbuffer"});
    if (o.has("cold")) m.options.cold = o.vec3("cold");
    if (o.has("warm")) m.options.warm = o.vec3("warm");
    m.label = "depth-usm-" + m.options.op;
  }
  if (m.method == "depth-usm" || m.method == "usm2d") {
    m.options.space = o.choice("space", "rgb", {"rgb", "lab"});
    if (m.options.space == "lab") m.label += "-lab";
  }
  if (m.method == "cornsweet") {
    m.options.cornsweet_mode = o.choice("mode", "image", {"image", "surface"});
    m.options.cornsweet_amplitude = o.number_or("amplitude", 4.0);
    if (o.has("edge_point")) m.options.edge_point = o.vec3("edge_point");
    if (o.has("edge_direction")) m.options.edge_direction = o.vec3("edge_direction");
    if (o.has("bright_normal")) m.options.bright_normal = o.vec3("bright_normal");
    m.label = "cornsweet-" + m.options.cornsweet_mode;
  }
  if (o.has("scenes")) {
    for (const auto& s : o.raw("scenes")) {
      if (!s.is_string()) o.fail("scenes", "expected a list of scene names");
      m.scenes.push_back(s.get<std::string>());
    }
  }
  if (o.has("label")) m.label = o.string("label");
  // Every σ must be acceptable to the method.
  for (double s : m.sigmas) {
    if (m.method == "none") break;
    try {
      method->validate(m.for_sigma(s));
    } catch (const InputError& e) {
      o.fail(m.sigma_key, std::string("σ = ") + format_value(s) + ": " + e.what());
    }
  }
  o.finish();
  return m;
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
  if (root.has("adjust")) root.object("adjust");  // the adjustment procedure; checked by `adjust`
  e.seed = uint64_t(root.integer_in("seed", 1, 0, 1ll << 53));
  if (root.has("lambda")) {
    JsonObject l = root.object("lambda");
    e.lambda.min = l.number_or("min", 0.0);
    e.lambda.max = l.number_or("max", 3.0);
    e.lambda.step = l.number_or("step", 0.05);
    if (!(e.lambda.step > 0)) l.fail("step", "must be positive");
    if (e.lambda.max < e.lambda.min) l.fail("max", "the λ range is empty (max < min)");
    if (e.lambda.count() > 100000) l.fail("step", "more than 100000 λ values");
    l.finish();
  }
  if (root.has("output")) {
    JsonObject out = root.object("output");
    e.bits = int(out.integer_or("bits", 8));
    if (e.bits != 8 && e.bits != 16) out.fail("bits", "must be 8 or 16");
    out.finish();
  }
  if (root.has("contact_sheet")) {
    JsonObject c = root.object("contact_sheet");
    e.contact_columns = int(c.integer_in("columns", 6, 2, 32));
    c.finish();
  }
  std::set<std::string> names;
  const std::filesystem::path base = path.parent_path();
  for (const auto& s : root.objects("scenes")) {
    ExperimentScene scene;
    scene.name = s.string("name");
    if (scene.name.empty() || scene.name.find_first_of("/\\. ") != std::string::npos)
      s.fail("name", "must be a plain name (no '/', '\\\\', '.' or spaces): it becomes a folder");
    if (!names.insert(scene.name).second) s.fail("name", "duplicate scene name '" + scene.name + "'");
    std::filesystem::path file = s.string("file");
    scene.file = file.is_absolute() ? file : base / file;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(scene.file, ec)) s.fail("file", "unknown scene: no such file " + scene.file.string());
    if (s.has("width")) scene.width = int(s.integer_in("width", 0, 1, 16384));
    if (s.has("height")) scene.height = int(s.integer_in("height", 0, 1, 16384));
    if (s.has("spp")) scene.spp = int(s.integer_in("spp", 0, 1, 65536));
    s.finish();
    e.scenes.push_back(scene);
  }
  if (e.scenes.empty()) root.fail("scenes", "an experiment needs at least one scene");
  std::set<std::string> labels;
  for (const auto& m : root.objects("methods")) {
    e.methods.push_back(parse_method(m));
    if (!labels.insert(e.methods.back().label).second)
      m.fail("method", "two methods share the folder '" + e.methods.back().label + "' (give one a \"label\")");
  }
  if (e.methods.empty()) root.fail("methods", "an experiment needs at least one method");
  for (const auto& m : e.methods)
    for (const auto& s : m.scenes)
      if (!names.count(s)) throw_input_error(path.string() + ": methods", "method '" + m.label + "' names an unknown scene '" + s + "'");
  root.finish();
  return e;
}

Scene load_experiment_scene(const Experiment& experiment, const ExperimentScene& s) {
  Scene scene = load_scene(s.file);
  if (s.width) scene.camera.width = *s.width;
  if (s.height) scene.camera.height = *s.height;
  if (s.spp) scene.settings.spp = *s.spp;
  scene.settings.seed = experiment.seed;
  return scene;
}

}  // namespace countershade
