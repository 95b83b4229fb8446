#include "stimuli/stimulus_set.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <ctime>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/progress.h"
#include "core/sha256.h"
#include "core/version.h"
#include "render/ray_tracer.h"
#include "stimuli/contact_sheet.h"

namespace countershade {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::string utc_now() {
  std::time_t t = std::time(nullptr);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buffer;
}

// One unit of work: a scene's reference image, or one (method, σ) of a scene with all its λ.
struct Unit {
  size_t scene;
  int method;  // -1: the reference image
  size_t sigma;
};

std::vector<Unit> all_units(const Experiment& e) {
  std::vector<Unit> units;
  for (size_t s = 0; s < e.scenes.size(); ++s) {
    units.push_back({s, -1, 0});
    for (size_t m = 0; m < e.methods.size(); ++m)
      if (e.methods[m].applies_to(e.scenes[s].name))
        for (size_t g = 0; g < e.methods[m].sigmas.size(); ++g) units.push_back({s, int(m), g});
  }
  return units;
}

std::string reference_path(const Experiment& e, size_t scene) { return e.scenes[scene].name + "/reference.png"; }

std::string stimulus_path(const Experiment& e, const Unit& u, int lambda_index) {
  const ExperimentMethod& m = e.methods[size_t(u.method)];
  return e.scenes[u.scene].name + "/" + m.label + "/sigma-" + format_value(m.sigmas[u.sigma]) + "/lambda-" +
         format_value(e.lambda.value(lambda_index)) + ".png";
}

std::string manifest_name(const GenerateOptions& o) {
  return o.shards == 1 ? "manifest.json"
                       : "manifest.shard-" + std::to_string(o.shard) + "-of-" + std::to_string(o.shards) + ".json";
}

std::string journal_name(const GenerateOptions& o) {
  return ".journal.shard-" + std::to_string(o.shard) + "-of-" + std::to_string(o.shards) + ".jsonl";
}

OrderedJson manifest_header(const Experiment& e) {
  OrderedJson m;
  m["format_version"] = kManifestFormatVersion;
  m["software_version"] = kVersion;
  m["experiment_name"] = e.name;
  m["experiment_sha256"] = e.sha256;
  m["experiment"] = OrderedJson::parse(e.content.dump());
  m["seed"] = e.seed;
  m["bits"] = e.bits;
  m["lambda_grid"] = {{"min", e.lambda.min}, {"max", e.lambda.max}, {"step", e.lambda.step}, {"count", e.lambda.count()}};
  return m;
}

void sort_entries(OrderedJson& stimuli) {
  std::vector<OrderedJson> list(stimuli.begin(), stimuli.end());
  std::sort(list.begin(), list.end(), [](const OrderedJson& a, const OrderedJson& b) {
    return a["file"].get<std::string>() < b["file"].get<std::string>();
  });
  stimuli = OrderedJson(list);
}

void write_json(const fs::path& path, const OrderedJson& json) { write_text_atomically(path, json.dump(2) + "\n"); }

// Appends one line and forces it to disk, so a killed run loses at most the image in flight.
class Journal {
 public:
  explicit Journal(const fs::path& path) : fd_(::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644)) {
    if (fd_ < 0) throw std::runtime_error(path.string() + ": cannot open the journal");
  }
  ~Journal() {
    if (fd_ >= 0) ::close(fd_);
  }
  void append(const OrderedJson& entry) {
    std::string line = entry.dump() + "\n";
    std::lock_guard<std::mutex> lock(mutex_);
    if (::write(fd_, line.data(), line.size()) != ssize_t(line.size()) || ::fsync(fd_) != 0)
      throw std::runtime_error("cannot write the journal");
  }

 private:
  int fd_;
  std::mutex mutex_;
};

// Entries of a previous run whose files are still there with the same checksum. The journal's
// first line names the experiment it belongs to; another experiment's journal is refused.
std::map<std::string, OrderedJson> verified_journal(const fs::path& set_dir, const fs::path& journal,
                                                    const std::string& experiment_sha256) {
  std::map<std::string, OrderedJson> done;
  std::ifstream in(journal);
  std::string line;
  while (std::getline(in, line)) {
    OrderedJson entry;
    try {
      entry = OrderedJson::parse(line);
    } catch (const std::exception&) {
      continue;  // a line cut by the interruption
    }
    if (entry.contains("experiment_sha256") && entry["experiment_sha256"] != experiment_sha256)
      throw_input_error(set_dir.string(), "the unfinished set there was made from a different experiment file; "
                                          "resume it with that file or choose a new folder");
    if (!entry.contains("file") || !entry.contains("sha256")) continue;
    fs::path file = set_dir / entry["file"].get<std::string>();
    std::error_code ec;
    if (fs::is_regular_file(file, ec) && sha256_file(file) == entry["sha256"].get<std::string>())
      done[entry["file"].get<std::string>()] = entry;
  }
  return done;
}

// Writes one stimulus and returns its manifest entry.
OrderedJson write_stimulus(const fs::path& set_dir, const std::string& relative, const Image& display, int bits,
                           OrderedJson entry) {
  fs::path file = set_dir / relative;
  fs::create_directories(file.parent_path());
  write_image(file, display, {bits});
  OrderedJson out;
  out["file"] = relative;
  for (auto it = entry.begin(); it != entry.end(); ++it) out[it.key()] = it.value();
  out["width"] = display.width;
  out["height"] = display.height;
  out["size"] = fs::file_size(file);
  out["sha256"] = sha256_file(file);
  return out;
}

// A run killed while writing leaves its temporary file (".<name>.tmp-<pid>-<n>.<ext>", see
// write_atomically) behind; the finished images never have that form.
void remove_interrupted_writes(const fs::path& dir) {
  std::vector<fs::path> leftovers;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    std::string name = entry.path().filename().string();
    if (entry.is_regular_file() && name.size() > 1 && name[0] == '.' && name.find(".tmp-") != std::string::npos)
      leftovers.push_back(entry.path());
  }
  for (const auto& p : leftovers) fs::remove(p);
}

void check_writable(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw_input_error(dir.string(), "cannot create the output folder (" + ec.message() + ")");
  fs::path probe = dir / ".countershade-write-test";
  {
    std::ofstream out(probe);
    if (!out) throw_input_error(dir.string(), "the output folder is not writable");
  }
  fs::remove(probe, ec);
}

void write_contact_sheets(const Experiment& e, const fs::path& dir, const OrderedJson& manifest) {
  std::set<std::string> files;
  for (const auto& s : manifest["stimuli"]) files.insert(s["file"].get<std::string>());
  // Evenly spaced λ columns, the first and the last included.
  const int count = e.lambda.count(), columns = std::min(e.contact_columns, count);
  std::vector<int> picks;
  for (int c = 0; c < columns; ++c) picks.push_back(columns == 1 ? 0 : int(std::lround(double(c) * (count - 1) / (columns - 1))));
  fs::create_directories(dir / "contact-sheets");
  for (size_t s = 0; s < e.scenes.size(); ++s)
    for (size_t m = 0; m < e.methods.size(); ++m) {
      if (!e.methods[m].applies_to(e.scenes[s].name)) continue;
      std::vector<std::string> rows, cols;
      std::vector<std::vector<fs::path>> cells;
      for (int p : picks) cols.push_back("lambda = " + format_value(e.lambda.value(p)));  // ASCII: OIIO text
      for (size_t g = 0; g < e.methods[m].sigmas.size(); ++g) {
        rows.push_back("sigma = " + format_value(e.methods[m].sigmas[g]));
        cells.emplace_back();
        for (int p : picks) {
          std::string rel = stimulus_path(e, {s, int(m), g}, p);
          if (!files.count(rel)) return;  // incomplete (a shard): no sheets
          cells.back().push_back(dir / rel);
        }
      }
      write_contact_sheet(dir / "contact-sheets" / (e.scenes[s].name + "-" + e.methods[m].label + ".png"),
                          e.scenes[s].name + " - " + e.methods[m].label, rows, cols, cells);
    }
}

}  // namespace

std::pair<int, int> parse_shard(const std::string& text) {
  int i = 0, n = 0;
  char slash = 0;
  std::istringstream in(text);
  if (!(in >> i >> slash >> n) || slash != '/' || !(in >> std::ws).eof() || n < 1 || i < 1 || i > n)
    throw InputError("--shard: expected I/N with 1 ≤ I ≤ N, got '" + text + "'");
  return {i, n};
}

GenerateReport generate_stimulus_set(const Experiment& e, const fs::path& dir, const GenerateOptions& options) {
  auto start = Clock::now();
  const std::string started = utc_now();
  check_writable(dir);
  const fs::path manifest_path = dir / manifest_name(options), journal_path = dir / journal_name(options);
  std::error_code ec;
  if (!options.resume && (fs::exists(manifest_path, ec) || fs::exists(journal_path, ec)))
    throw_input_error(dir.string(), "already holds a stimulus set (" +
                                        (fs::exists(manifest_path) ? manifest_name(options) : journal_name(options)) +
                                        "); use --resume to finish it or choose a new folder");
  std::map<std::string, OrderedJson> done;
  if (options.resume) {
    remove_interrupted_writes(dir);
    done = verified_journal(dir, journal_path, e.sha256);
  }

  // Every scene is loaded (and so checked) before anything renders.
  std::vector<Scene> scenes;
  for (const auto& s : e.scenes) scenes.push_back(load_experiment_scene(e, s));

  std::vector<Unit> units;
  {
    auto all = all_units(e);
    for (size_t k = 0; k < all.size(); ++k)
      if (int(k % size_t(options.shards)) == options.shard - 1) units.push_back(all[k]);
  }
  const int lambdas = e.lambda.count();
  size_t total = 0;
  for (const auto& u : units) total += u.method < 0 ? 1 : size_t(lambdas);

  GenerateReport report;
  OrderedJson stimuli = OrderedJson::array();
  const bool new_journal = !fs::exists(journal_path, ec);
  Journal journal(journal_path);
  if (new_journal) journal.append({{"experiment_sha256", e.sha256}});
  Progress progress("stimuli " + e.name);
  std::atomic<size_t> finished{0}, written{0}, skipped{0};
  std::mutex stimuli_mutex;
  std::atomic<double> compose_seconds{0}, encode_seconds{0};
  tbb::task_arena arena(options.jobs > 0 ? options.jobs : tbb::this_task_arena::max_concurrency());

  auto record = [&](OrderedJson entry, bool is_new) {
    if (is_new) journal.append(entry);
    {
      std::lock_guard<std::mutex> lock(stimuli_mutex);
      stimuli.push_back(std::move(entry));
    }
    ++(is_new ? written : skipped);
    progress.update(double(++finished) / double(std::max<size_t>(total, 1)));
  };

  for (size_t s = 0; s < e.scenes.size(); ++s) {
    std::vector<Unit> mine;
    for (const auto& u : units)
      if (u.scene == s) mine.push_back(u);
    if (mine.empty()) continue;
    // Skip the render when every image of this scene is already done.
    bool all_done = true;
    for (const auto& u : mine) {
      if (u.method < 0) all_done &= done.count(reference_path(e, s)) > 0;
      else
        for (int l = 0; l < lambdas && all_done; ++l) all_done &= done.count(stimulus_path(e, u, l)) > 0;
    }
    if (all_done) {
      for (const auto& u : mine) {
        if (u.method < 0) record(done[reference_path(e, s)], false);
        else
          for (int l = 0; l < lambdas; ++l) record(done[stimulus_path(e, u, l)], false);
      }
      continue;
    }
    bool needs_vertices = false;
    for (const auto& u : mine) needs_vertices |= u.method >= 0 && find_method(e.methods[size_t(u.method)].method)->needs_vertex_radiance();
    int ring = 0;
    for (const auto& u : mine)
      if (u.method >= 0 && e.methods[size_t(u.method)].method == "usm3d") ring = std::max(ring, e.methods[size_t(u.method)].ring_samples);

    auto t0 = Clock::now();
    View view;
    arena.execute([&] {
      RayTracer tracer(scenes[s]);
      RenderOptions ro;
      ro.threads = options.jobs;
      ro.vertex_radiance = needs_vertices;
      ro.ring_samples = ring;
      view = make_view(scenes[s], render(scenes[s], tracer, ro), e.bits);
    });
    report.render_seconds += since(t0);
    const std::string encoding = scenes[s].display.encoding.describe();

    for (const auto& u : mine) {
      if (u.method < 0) {
        std::string rel = reference_path(e, s);
        if (done.count(rel)) {
          record(done[rel], false);
          continue;
        }
        auto te = Clock::now();
        OrderedJson entry = write_stimulus(dir, rel, view.display, e.bits,
                                           {{"scene", e.scenes[s].name}, {"method", "none"}, {"lambda", 0.0},
                                            {"lambda_index", 0}, {"clipped_pixels", 0}, {"display_encoding", encoding}});
        encode_seconds.fetch_add(since(te));
        record(entry, true);
        continue;
      }
      const ExperimentMethod& m = e.methods[size_t(u.method)];
      auto tp = Clock::now();
      std::unique_ptr<PreparedEnhancement> prepared;
      arena.execute([&] { prepared = find_method(m.method)->prepare(view, m.for_sigma(m.sigmas[u.sigma])); });
      report.prepare_seconds += since(tp);
      OrderedJson parameters = OrderedJson::parse(prepared->parameters().dump());
      arena.execute([&] {
        tbb::parallel_for(0, lambdas, [&](int l) {
          std::string rel = stimulus_path(e, u, l);
          if (done.count(rel)) {
            record(done[rel], false);
            return;
          }
          auto tc = Clock::now();
          Composed c = prepared->compose(e.lambda.value(l));
          compose_seconds.fetch_add(since(tc));
          auto te = Clock::now();
          OrderedJson info = {{"scene", e.scenes[s].name},   {"method", m.method},
                              {"label", m.label},            {"sigma", m.sigmas[u.sigma]},
                              {"sigma_kind", m.sigma_key},   {"lambda", e.lambda.value(l)},
                              {"lambda_index", l},           {"clipped_pixels", c.clipped_pixels},
                              {"parameters", parameters}};
          if (m.method == "depth-usm") info["operator"] = m.options.op;
          if (parameters.contains("iterations")) info["iterations"] = parameters["iterations"];
          OrderedJson entry = write_stimulus(dir, rel, c.display, e.bits, info);
          encode_seconds.fetch_add(since(te));
          record(entry, true);
        });
      });
    }
  }

  sort_entries(stimuli);
  report.images_written = written;
  report.images_skipped = skipped;
  OrderedJson manifest = manifest_header(e);
  if (options.shards > 1) manifest["shard"] = {{"index", options.shard}, {"count", options.shards}};
  manifest["stimuli"] = stimuli;
  report.compose_seconds = compose_seconds;
  report.encode_seconds = encode_seconds;
  report.total_seconds = since(start);
  manifest["run"] = {{"started_utc", started}, {"finished_utc", utc_now()}, {"jobs", options.jobs},
                     {"seconds", {{"render", report.render_seconds}, {"prepare", report.prepare_seconds},
                                  {"compose", report.compose_seconds}, {"encode", report.encode_seconds},
                                  {"total", report.total_seconds}}}};
  write_json(manifest_path, manifest);
  fs::remove(journal_path, ec);
  if (options.contact_sheets && options.shards == 1) write_contact_sheets(e, dir, manifest);
  report.manifest = manifest_path;
  progress.finish("wrote " + manifest_path.string() + " (" + std::to_string(stimuli.size()) + " images, " +
                  format_seconds(report.total_seconds) + ")");
  return report;
}

fs::path merge_shard_manifests(const Experiment& e, const fs::path& dir) {
  std::map<int, OrderedJson> shards;
  int count = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    std::string name = entry.path().filename().string();
    if (name.rfind("manifest.shard-", 0) != 0) continue;
    OrderedJson m = read_manifest(entry.path());
    if (m["experiment_sha256"] != e.sha256)
      throw_input_error(entry.path().string(), "was made from a different experiment file");
    int index = m["shard"]["index"], n = m["shard"]["count"];
    if (count && n != count) throw_input_error(entry.path().string(), "belongs to a split into a different number of shards");
    count = n;
    shards[index] = m;
  }
  if (!count) throw_input_error(dir.string(), "no shard manifests (manifest.shard-I-of-N.json) to merge");
  for (int i = 1; i <= count; ++i)
    if (!shards.count(i)) throw_input_error(dir.string(), "shard " + std::to_string(i) + " of " + std::to_string(count) + " is missing");
  OrderedJson manifest = manifest_header(e);
  OrderedJson stimuli = OrderedJson::array();
  std::string started = "9999", finished = "0000";
  for (auto& [i, m] : shards) {
    for (auto& s : m["stimuli"]) stimuli.push_back(s);
    started = std::min(started, m["run"]["started_utc"].get<std::string>());
    finished = std::max(finished, m["run"]["finished_utc"].get<std::string>());
  }
  sort_entries(stimuli);
  manifest["stimuli"] = stimuli;
  manifest["run"] = {{"started_utc", started}, {"finished_utc", finished}, {"merged_shards", count}};
  write_json(dir / "manifest.json", manifest);
  write_contact_sheets(e, dir, manifest);
  return dir / "manifest.json";
}

}  // namespace countershade
