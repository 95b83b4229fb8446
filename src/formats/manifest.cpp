#include "formats/manifest.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/file_bytes.h"
#include "core/json_reader.h"
#include "core/sha256.h"
#include "formats/responses.h"

namespace countershade {

namespace fs = std::filesystem;

namespace {

const std::set<std::string> kEntryKeys = {
    "file",           "scene", "method", "label", "sigma",  "sigma_kind", "lambda", "lambda_index",
    "clipped_pixels", "width", "height", "size",  "sha256", "frame",      "fps"};

class ManifestReader {
 public:
  explicit ManifestReader(const fs::path& path) : path_(path) {}

  [[noreturn]] void fail(const std::string& field, const std::string& what) const {
    throw_input_error(path_.string() + ": " + field, what);
  }
  const OrderedJson& need(const OrderedJson& o, const std::string& where, const char* key) const {
    if (!o.contains(key)) fail(where + key, "missing");
    return o[key];
  }
  std::string string(const OrderedJson& o, const std::string& where, const char* key) const {
    const OrderedJson& v = need(o, where, key);
    if (!v.is_string()) fail(where + key, "not a string");
    return v.get<std::string>();
  }
  double number(const OrderedJson& o, const std::string& where, const char* key) const {
    const OrderedJson& v = need(o, where, key);
    if (!v.is_number()) fail(where + key, "not a number");
    return v.get<double>();
  }
  // A λ as stimulus grids hold them (formats/responses.h): the app records it as the answer.
  double lambda(const OrderedJson& o, const std::string& where, const char* key) const {
    const double v = number(o, where, key);
    if (std::abs(v) > kLargestLambda)
      fail(where + key, "beyond ±1e6, which no stimulus grid holds");
    return v;
  }
  int64_t integer(const OrderedJson& o, const std::string& where, const char* key, int64_t lo,
                  int64_t hi) const {
    const OrderedJson& v = need(o, where, key);
    if (!v.is_number_integer()) fail(where + key, "not an integer");
    int64_t i = v.is_number_unsigned() && v.get<uint64_t>() > uint64_t(INT64_MAX)
                    ? INT64_MAX
                    : v.get<int64_t>();
    if (i < lo || i > hi)
      fail(where + key, "out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return i;
  }

  ManifestEntry entry(const OrderedJson& s, size_t i) const {
    const std::string where = "stimuli[" + std::to_string(i) + "].";
    if (!s.is_object()) fail("stimuli[" + std::to_string(i) + "]", "not an object");
    ManifestEntry e;
    e.file = string(s, where, "file");
    try {
      resolve_in_set(path_.parent_path(), e.file);
    } catch (const InputError& error) {
      fail(where + "file", error.what());
    }
    e.scene = string(s, where, "scene");
    e.method = string(s, where, "method");
    e.sha256 = string(s, where, "sha256");
    e.width = int(integer(s, where, "width", 1, 1 << 20));
    e.height = int(integer(s, where, "height", 1, 1 << 20));
    if (s.contains("label")) e.label = string(s, where, "label");
    if (s.contains("sigma")) e.sigma = number(s, where, "sigma");
    if (s.contains("sigma_kind")) e.sigma_kind = string(s, where, "sigma_kind");
    if (s.contains("lambda")) e.lambda = lambda(s, where, "lambda");
    if (s.contains("lambda_index"))
      e.lambda_index = int(integer(s, where, "lambda_index", 0, 1 << 30));
    if (s.contains("clipped_pixels"))
      e.clipped_pixels = uint64_t(integer(s, where, "clipped_pixels", 0, INT64_MAX));
    if (s.contains("size")) e.size = uint64_t(integer(s, where, "size", 0, INT64_MAX));
    if (s.contains("frame") || s.contains("fps")) {  // a sequence's frame has both
      e.frame = ManifestEntry::Frame{int(integer(s, where, "frame", 0, 1 << 30)),
                                     number(s, where, "fps")};
      if (!(e.frame->fps > 0)) fail(where + "fps", "must be positive");
    }
    if (!e.is_reference()) {
      for (const char* key : {"sigma", "lambda", "lambda_index"})
        if (!s.contains(key)) fail(where + key, "missing (every enhanced stimulus has one)");
    }
    for (auto it = s.begin(); it != s.end(); ++it)
      if (!kEntryKeys.count(it.key())) e.extra[it.key()] = it.value();
    return e;
  }

  Manifest read(const OrderedJson& m) const {
    if (!m.is_object()) fail("", "expected an object");
    Manifest out;
    if (!m.contains("format_version") || m["format_version"] != kManifestFormatVersion)
      fail("format_version",
           "missing or unsupported (expected " + std::to_string(kManifestFormatVersion) + ")");
    if (!m.contains("stimuli") || !m["stimuli"].is_array())
      fail("stimuli", "missing or not an array");
    out.software_version = m.value("software_version", "");
    out.experiment_name = m.value("experiment_name", path_.parent_path().filename().string());
    out.experiment_sha256 = m.value("experiment_sha256", "");
    if (m.contains("experiment")) out.experiment = m["experiment"];
    if (m.contains("seed")) out.seed = uint64_t(integer(m, "", "seed", 0, INT64_MAX));
    if (m.contains("bits")) out.bits = int(integer(m, "", "bits", 1, 32));
    if (m.contains("lambda_grid")) out.lambda_grid = grid(m["lambda_grid"]);
    if (m.contains("shard")) {
      const OrderedJson& sh = m["shard"];
      out.shard = std::make_pair(int(integer(sh, "shard.", "index", 1, 1 << 20)),
                                 int(integer(sh, "shard.", "count", 1, 1 << 20)));
    }
    for (size_t i = 0; i < m["stimuli"].size(); ++i)
      out.stimuli.push_back(entry(m["stimuli"][i], i));
    if (m.contains("videos")) out.videos = videos(m["videos"]);
    if (m.contains("viewing")) out.viewing = viewing(m["viewing"]);
    if (m.contains("run")) out.run = m["run"];
    return out;
  }

  Viewing viewing(const OrderedJson& v) const {
    if (!v.is_object()) fail("viewing", "not an object");
    Viewing out;
    out.pixels_per_degree = number(v, "viewing.", "pixels_per_degree");
    const OrderedJson& screen = need(v, "viewing.", "screen");
    out.width_mm = number(screen, "viewing.screen.", "width_mm");
    out.distance_mm = number(screen, "viewing.screen.", "distance_mm");
    out.width_px = int(integer(screen, "viewing.screen.", "width_px", 1, 1 << 16));
    if (!(*out.pixels_per_degree > 0 && out.width_mm > 0 && out.distance_mm > 0))
      fail("viewing", "pixels_per_degree, width_mm and distance_mm must be positive");
    return out;
  }

  OrderedJson videos(const OrderedJson& v) const {
    if (!v.is_array()) fail("videos", "not an array");
    for (size_t i = 0; i < v.size(); ++i) {
      const std::string where = "videos[" + std::to_string(i) + "].";
      if (!v[i].is_object()) fail("videos[" + std::to_string(i) + "]", "not an object");
      string(v[i], where, "sha256");
      try {
        resolve_in_set(path_.parent_path(), string(v[i], where, "file"));
      } catch (const InputError& error) {
        fail(where + "file", error.what());
      }
    }
    return v;
  }

  LambdaGridInfo grid(const OrderedJson& g) const {
    if (!g.is_object()) fail("lambda_grid", "not an object");
    LambdaGridInfo out;
    out.min = lambda(g, "lambda_grid.", "min");
    out.step = lambda(g, "lambda_grid.", "step");
    out.count = int(integer(g, "lambda_grid.", "count", 1, kMostLambdaValues));
    out.max =
        g.contains("max") ? lambda(g, "lambda_grid.", "max") : out.min + out.step * (out.count - 1);
    return out;
  }

 private:
  fs::path path_;
};

}  // namespace

fs::path resolve_in_set(const fs::path& set_dir, const std::string& relative) {
  fs::path p(relative);
  if (relative.empty() || p.is_absolute())
    throw InputError("path '" + relative + "' must be relative to the set folder");
  for (const auto& part : p)
    if (part == "..") throw InputError("path '" + relative + "' leaves the set folder");
  return set_dir / p;
}

ManifestEntry parse_manifest_entry(const OrderedJson& json, const fs::path& file, size_t index) {
  return ManifestReader(file).entry(json, index);
}

OrderedJson to_json(const ManifestEntry& e) {
  OrderedJson j;
  j["file"] = e.file;
  j["scene"] = e.scene;
  j["method"] = e.method;
  if (!e.label.empty()) j["label"] = e.label;
  if (e.sigma) j["sigma"] = *e.sigma;
  if (!e.sigma_kind.empty()) j["sigma_kind"] = e.sigma_kind;
  j["lambda"] = e.lambda;
  j["lambda_index"] = e.lambda_index;
  j["clipped_pixels"] = e.clipped_pixels;
  if (e.frame) {
    j["frame"] = e.frame->index;
    j["fps"] = e.frame->fps;
  }
  for (auto it = e.extra.begin(); it != e.extra.end(); ++it) j[it.key()] = it.value();
  j["width"] = e.width;
  j["height"] = e.height;
  j["size"] = e.size;
  j["sha256"] = e.sha256;
  return j;
}

OrderedJson to_json(const Manifest& m) {
  OrderedJson j;
  j["format_version"] = m.format_version;
  j["software_version"] = m.software_version;
  j["experiment_name"] = m.experiment_name;
  j["experiment_sha256"] = m.experiment_sha256;
  j["experiment"] = m.experiment;
  j["seed"] = m.seed;
  j["bits"] = m.bits;
  j["lambda_grid"] = {{"min", m.lambda_grid.min},
                      {"max", m.lambda_grid.max},
                      {"step", m.lambda_grid.step},
                      {"count", m.lambda_grid.count}};
  if (m.shard) j["shard"] = {{"index", m.shard->first}, {"count", m.shard->second}};
  j["stimuli"] = OrderedJson::array();
  for (const auto& e : m.stimuli) j["stimuli"].push_back(to_json(e));
  if (!m.videos.empty()) j["videos"] = m.videos;
  if (!m.viewing.empty())
    j["viewing"] = {{"pixels_per_degree", *m.viewing.pixels_per_degree},
                    {"screen",
                     {{"width_mm", m.viewing.width_mm},
                      {"width_px", m.viewing.width_px},
                      {"distance_mm", m.viewing.distance_mm}}}};
  j["run"] = m.run;
  return j;
}

Manifest read_manifest(const fs::path& path) {
  const std::string bytes = read_file_bytes(path);
  Manifest m = ManifestReader(path).read(parse_ordered_json_text(bytes, path.string()));
  m.file_sha256 = sha256_hex(bytes);
  return m;
}

void write_manifest(const fs::path& path, const Manifest& manifest) {
  write_text_atomically(path, to_json(manifest).dump(2) + "\n");
}

namespace {

// A file a stimulus names in entry.extra[key] as {"file", "sha256"}: its congruence map, or the
// method's mask of a sequence frame (several entries may name one mask; it is checked once).
void check_named_file(const fs::path& dir, const ManifestEntry& s, const char* key,
                      std::set<fs::path>& listed, std::vector<std::string>& problems) {
  if (!s.extra.contains(key)) return;
  const OrderedJson& named = s.extra[key];
  if (!named.is_object() || !named.contains("file") || !named["file"].is_string() ||
      !named.contains("sha256")) {
    problems.push_back(s.file + ": " + key + " needs a file and a sha256");
    return;
  }
  const std::string rel = named["file"].get<std::string>();
  const fs::path file = resolve_in_set(dir, rel);
  if (!listed.insert(fs::weakly_canonical(file)).second) return;
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    problems.push_back(rel + ": missing");
  else if (sha256_file(file) != named["sha256"])
    problems.push_back(rel + ": sha256 differs from the manifest");
}

}  // namespace

std::vector<std::string> verify_stimulus_set(const fs::path& manifest_path) {
  Manifest manifest = read_manifest(manifest_path);
  const auto dir = manifest_path.parent_path();
  std::vector<std::string> problems;
  std::set<fs::path> listed;
  for (const auto& s : manifest.stimuli) {
    auto file = resolve_in_set(dir, s.file);
    listed.insert(fs::weakly_canonical(file));
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) {
      problems.push_back(s.file + ": missing");
      continue;
    }
    if (s.size && fs::file_size(file) != s.size)
      problems.push_back(s.file + ": size differs from the manifest");
    if (sha256_file(file) != s.sha256)
      problems.push_back(s.file + ": sha256 differs from the manifest");
    check_named_file(dir, s, "congruence_map", listed, problems);
    check_named_file(dir, s, "mask", listed, problems);
  }
  for (const auto& video : manifest.videos) {
    const std::string rel = video["file"].get<std::string>();
    const fs::path file = resolve_in_set(dir, rel);
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
      problems.push_back(rel + ": missing");
    else if (sha256_file(file) != video["sha256"])
      problems.push_back(rel + ": sha256 differs from the manifest");
  }
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file() || entry.path().extension() != ".png") continue;
    auto rel = fs::relative(entry.path(), dir).string();
    if (rel.rfind("contact-sheets", 0) == 0) continue;
    if (!listed.count(fs::weakly_canonical(entry.path())))
      problems.push_back(rel + ": not in the manifest");
  }
  return problems;
}

OrderedJson reproducible_part(const Manifest& manifest) {
  OrderedJson copy = to_json(manifest);
  copy.erase("run");
  return copy;
}

void sort_entries(std::vector<ManifestEntry>& entries) {
  std::sort(entries.begin(), entries.end(),
            [](const ManifestEntry& a, const ManifestEntry& b) { return a.file < b.file; });
}

void set_image_noise(ManifestEntry& entry, const ImageNoise& noise) {
  OrderedJson& j = entry.extra["noise"];
  j = {{"rms", noise.rms}, {"p99", noise.p99}};
  if (noise.budget)
    j["budget"] = {
        {"target", noise.budget->target}, {"p99", noise.budget->p99}, {"met", noise.budget->met}};
}

std::optional<ImageNoise> image_noise(const ManifestEntry& entry) {
  const auto j = entry.extra.find("noise");
  if (j == entry.extra.end() || !j->is_object() || !j->contains("rms")) return std::nullopt;
  ImageNoise noise;
  noise.rms = (*j)["rms"].get<double>();
  noise.p99 = j->value("p99", 0.0);
  if (j->contains("budget")) {
    const OrderedJson& b = (*j)["budget"];
    noise.budget =
        ImageNoise::Budget{b.value("target", 0.0), b.value("p99", 0.0), b.value("met", false)};
  }
  return noise;
}

Manifest read_verified_manifest(const std::filesystem::path& manifest_path) {
  Manifest manifest = read_manifest(manifest_path);
  const auto problems = verify_stimulus_set(manifest_path);
  if (!problems.empty())
    throw_input_error(
        manifest_path.string(),
        "the set does not match its manifest (" + problems.front() +
            (problems.size() > 1 ? ", and " + std::to_string(problems.size() - 1) + " more" : "") +
            ")");
  return manifest;
}

}  // namespace countershade
