#include "stimuli/stimulus_set.h"

#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/false_colour.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/sha256.h"
#include "core/time.h"
#include "core/version.h"
#include "enhance/lightness.h"
#include "enhance/stimulus_noise.h"
#include "enhance/view_plan.h"
#include "measures/congruence.h"
#include "measures/perspective_coherence.h"
#include "measures/scale_against_depth.h"
#include "render/scene_animation.h"
#include "stimuli/headroom.h"
#include "stimuli/mask_file.h"
#include "stimuli/mean_hold.h"
#include "stimuli/sequence_flicker.h"
#include "stimuli/sequence_videos.h"
#include "stimuli/set_journal.h"
#include "stimuli/set_layout.h"

namespace countershade {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

Manifest manifest_header(const Experiment& e) {
  Manifest m;
  m.software_version = kVersion;
  m.experiment_name = e.name;
  m.experiment_sha256 = e.sha256;
  m.experiment = OrderedJson::parse(e.content.dump());
  m.seed = e.seed;
  m.bits = e.bits;
  m.lambda_grid = {e.lambda.min, e.lambda.max, e.lambda.step, e.lambda.count()};
  if (e.screen) {
    m.viewing.pixels_per_degree = e.screen->pixels_per_degree();
    m.viewing.width_mm = e.screen->width_mm;
    m.viewing.width_px = e.screen->width_px;
    m.viewing.distance_mm = e.screen->distance_mm;
  }
  return m;
}

void check_writable(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw_input_error(dir.string(), "cannot create the output folder (" + ec.message() + ")");
  fs::path probe = dir / ".countershade-write-test";
  {
    std::ofstream out(probe);
    if (!out) throw_input_error(dir.string(), "the output folder is not writable");
  }
  fs::remove(probe, ec);
}

// Writes one stimulus and completes its manifest entry with the file's facts.
ManifestEntry write_stimulus(const fs::path& set_dir, ManifestEntry entry, const Image& display,
                             int bits) {
  const fs::path file = set_dir / entry.file;
  fs::create_directories(file.parent_path());
  write_image(file, display, {bits});
  entry.width = display.width;
  entry.height = display.height;
  entry.size = fs::file_size(file);
  entry.sha256 = sha256_file(file);
  return entry;
}

// The manifest entry of a method's stimulus, before the file's facts are known.
ManifestEntry stimulus_entry(const Experiment& e, const SetUnit& u, int l, const Composed& c,
                             const nlohmann::json& parameters) {
  const ExperimentMethod& m = e.methods[size_t(u.method)];
  ManifestEntry entry;
  entry.file = stimulus_path(e, u, l);
  entry.scene = e.scenes[u.scene].name;
  entry.method = m.method->name();
  entry.label = m.label;
  entry.sigma = m.sigmas[u.sigma];
  entry.sigma_kind = m.sigma_key;
  entry.lambda = e.lambda.value(l);
  entry.lambda_index = l;
  entry.clipped_pixels = c.clipped_pixels;
  if (u.frame >= 0) entry.frame = ManifestEntry::Frame{u.frame, e.scenes[u.scene].fps};
  entry.extra["parameters"] = OrderedJson::parse(parameters.dump());
  // data-formats.md records these at the top level too, where a method has them.
  for (const char* key : {"operator", "iterations"})
    if (parameters.contains(key)) entry.extra[key] = entry.extra["parameters"][key];
  return entry;
}

// What every method applied to a scene needs from its one render.
RenderRequest scene_request(const Experiment& e, size_t scene) {
  RenderRequest request;
  for (const auto& m : e.methods)
    if (m.applies_to(e.scenes[scene].name))
      request.merge(m.request, e.file.string() + ": methods (" + m.label + ")");
  return request;
}

// Every (method, σ) applied to a scene, rendered for at once: the noise budget holds at the
// grid's strongest λ for all of them, the reference included.
struct ScenePlan {
  ViewPlan plan;
  std::map<std::pair<int, int>, size_t> use_of;  // (method, σ index) -> index into plan.uses
};

ScenePlan scene_plan(const Experiment& e, size_t scene) {
  ScenePlan out;
  out.plan.max_abs_lambda = std::max(std::abs(e.lambda.min), std::abs(e.lambda.max));
  for (size_t m = 0; m < e.methods.size(); ++m) {
    const ExperimentMethod& method = e.methods[m];
    if (!method.applies_to(e.scenes[scene].name)) continue;
    for (size_t s = 0; s < method.parameters.size(); ++s) {
      out.use_of[{int(m), int(s)}] = out.plan.uses.size();
      out.plan.uses.push_back({method.method, method.parameters[s], nlohmann::json::object()});
    }
  }
  return out;
}

// The noise estimate and sample counts of an image as written (docs/data-formats).
void record_noise(ManifestEntry& entry, const View& view, const NoiseModel& model,
                  const Image& written) {
  const NoiseBudget& budget = view.scene->settings.noise;
  const NoiseSummary noise = summarize_noise(stimulus_noise(view, model, written));
  const SamplingReport& sampling = view.render.sampling;
  const bool fixed = view.scene->settings.spp.has_value();
  ImageNoise recorded{round_to(noise.rms, 4), round_to(noise.p99, 4), std::nullopt};
  if (!fixed)
    recorded.budget = ImageNoise::Budget{budget.target, budget.p99,
                                         noise.rms <= budget.target && noise.p99 <= budget.p99};
  set_image_noise(entry, recorded);
  entry.extra["spp"] = {{"min", sampling.pixels.min},
                        {"mean", round_to(sampling.pixels.mean, 2)},
                        {"max", sampling.pixels.max}};
}

// The stimulus of strength λ with its reference's mean L* (the experiment's hold_mean), the
// offset composed by the method where it can; returns the L* offset.
double hold_mean(const View& view, const PreparedEnhancement& prepared, double lambda,
                 Composed& c) {
  HeldMean held = hold_mean_lightness(view, prepared, lambda, c);
  c.display = std::move(held.display);
  c.clipped_pixels = held.clipped_pixels;
  return held.offset;
}

// The congruence score of a stimulus, and its map in false colour as congruence/FILE.
void record_congruence(const fs::path& set_dir, ManifestEntry& entry, const Image& display,
                       const View& view, int bits, const CongruenceOptions& options) {
  const Congruence c = display_congruence(display, view.encoding, bits, view.depth, options);
  entry.extra["congruence"] = round_to(c.score, 4);
  const std::string map = "congruence/" + entry.file;
  fs::create_directories((set_dir / map).parent_path());
  write_image(set_dir / map, false_colour_image(c.map));
  entry.extra["congruence_map"] = {{"file", map}, {"sha256", sha256_file(set_dir / map)}};
}

// The stimulus's perspective coherence (for the reference: the plain render's own reprojection
// error), in L*, with the number of pixels it covers; given the plain render's own change per
// pixel, also over the pixels where it stays within kStableTolerance.
void record_coherence(ManifestEntry& entry, const View& view, const std::vector<float>& first,
                      const View& moved, const std::vector<float>& second,
                      const std::vector<float>* plain_differences = nullptr) {
  std::vector<float> differences;
  const Reprojection r = reprojection_rms(view, first, moved, second, {}, &differences);
  entry.extra["coherence"] = round_to(r.rms, 4);
  entry.extra["coherence_pixels"] = r.pixels;
  if (!plain_differences) return;
  const Reprojection stable = rms_where_stable(differences, *plain_differences, kStableTolerance);
  entry.extra["coherence_stable"] = round_to(stable.rms, 4);
  entry.extra["coherence_stable_pixels"] = stable.pixels;
}

// A sequence's frame keeps the method's mask, for its mask flicker (stimuli/sequence_flicker.h):
// its manifest record, or null for a still or a method without one.
nlohmann::json write_frame_mask(const fs::path& dir, const Experiment& e, const SetUnit& u,
                                const PreparedEnhancement& prepared, const View& view) {
  if (u.frame < 0) return nullptr;
  const std::vector<float> mask = prepared.mask();
  return mask.empty() ? nlohmann::json()
                      : write_mask(dir, mask_path(e, u), mask, view.width(), view.height());
}

// The halo widths of an edge probe's stimulus against depth, and their log-log slope
// (stimuli/scale_against_depth.h).
void record_halo_widths(ManifestEntry& entry, const View& view, const std::vector<float>& layer,
                        const std::vector<double>& edges_x) {
  const std::vector<HaloSample> samples =
      halo_samples({view.scene->camera, view.depth, layer}, edges_x);
  nlohmann::json edge = nlohmann::json::array(), depth = nlohmann::json::array(),
                 width = nlohmann::json::array();
  for (const HaloSample& s : samples) {
    edge.push_back(s.edge_x);
    depth.push_back(round_to(s.depth, 4));
    width.push_back(round_to(s.width_px, 3));
  }
  entry.extra["halo_widths"] = {{"edge_x", edge}, {"depth", depth}, {"width_px", width}};
  const DepthSlope slope = depth_slope(samples);
  entry.extra["depth_slope"] =
      std::isfinite(slope.slope) ? nlohmann::json(round_to(slope.slope, 4)) : nlohmann::json();
  entry.extra["depth_slope_samples"] = slope.samples;
}

// The plain render's own change per pixel under the dolly (empty without one).
std::vector<float> plain_differences(const View& view, const View* moved) {
  std::vector<float> differences;
  if (moved)
    reprojection_rms(view, view_lightness(view), *moved, view_lightness(*moved), {}, &differences);
  return differences;
}

// The view again with its camera dollied, for the coherence metric (null without one).
std::shared_ptr<const View> moved_view(const Experiment& e, const Scene& scene,
                                       const ViewPlan& plan, const ViewOptions& options) {
  if (!e.coherence_dolly) return nullptr;
  auto moved = std::make_shared<Scene>(scene);
  moved->camera = dollied(scene.camera, *e.coherence_dolly);
  return render_view(moved, plan, options);
}

// The units that share one render: a still scene's, or one frame's of a sequence.
using Shot = std::vector<SetUnit>;

// The units of `scene` grouped into shots, frame by frame.
std::vector<Shot> shots_of(size_t scene, const std::vector<SetUnit>& units) {
  std::map<int, Shot> by_frame;
  for (const auto& u : units)
    if (u.scene == scene) by_frame[u.frame].push_back(u);
  std::vector<Shot> shots;
  for (auto& [frame, shot] : by_frame) shots.push_back(std::move(shot));
  return shots;
}

// The scene as the set renders it: the experiment's overrides, every method's request applied,
// and checked by every method that applies to it.
std::shared_ptr<Scene> set_scene(const Experiment& e, size_t s) {
  auto scene = std::make_shared<Scene>(load_experiment_scene(e, e.scenes[s]));
  apply_request(*scene, scene_request(e, s));
  for (const ExperimentMethod& m : e.methods)
    if (m.applies_to(e.scenes[s].name))
      for (const auto& parameters : m.parameters) m.method->check_scene(*scene, *parameters);
  return scene;
}

// The end of a complete set, made in one run or merged from shards: the flicker measured from its
// files, the videos, and manifest.json with the run record `run()` gives at that moment. (The
// sheets and figures are drawn from the manifest afterwards: figures/set_figures.h.)
void finish_set(const Experiment& e, const fs::path& dir, Manifest& manifest,
                const std::function<std::shared_ptr<const Scene>(size_t)>& scene_of,
                const std::function<nlohmann::json()>& run, int jobs) {
  sort_entries(manifest.stimuli);
  for (size_t s = 0; s < e.scenes.size(); ++s)
    if (e.scenes[s].is_sequence())
      measure_sequence_flicker(e, dir, e.scenes[s], *scene_of(s), manifest.stimuli, jobs);
  if (e.video) write_sequence_videos(dir, manifest, jobs);
  manifest.run = run();
  write_manifest(dir / "manifest.json", manifest);
}

class SetGenerator {
 public:
  SetGenerator(const Experiment& e, const fs::path& dir, const GenerateOptions& options)
      : e_(e), dir_(dir), options_(options), progress_("stimuli " + e.name) {}

  GenerateReport run();

 private:
  void prepare_folder();
  void remove_own_interrupted_writes(const std::vector<SetUnit>& units) const;
  std::vector<SetUnit> shard_units() const;
  std::vector<std::string> files_of(const SetUnit& unit) const;
  bool all_done(const Shot& shot) const;
  void record(ManifestEntry entry, bool is_new);
  void make_shot(const Shot& shot, const ScenePlan& plan);
  std::shared_ptr<const View> headroom_view(size_t scene, const ScenePlan& plan,
                                            const ViewOptions& options);
  void write_reference(const SetUnit& unit, const View& view, const View* moved);
  // The method prepared for a grid of λ (each composed from the view's own samples).
  std::unique_ptr<PreparedEnhancement> prepare_for_grid(const ExperimentMethod& m, const SetUnit& u,
                                                        const std::shared_ptr<const View>& view,
                                                        size_t use) const;
  // `plain`: the plain render's own change per pixel under the dolly (with `moved`).
  void write_condition(const SetUnit& unit, const std::shared_ptr<const View>& view,
                       const std::shared_ptr<const View>& moved, const std::vector<float>& plain,
                       size_t use);
  void finish();

  const Experiment& e_;
  fs::path dir_, manifest_path_, journal_path_;
  GenerateOptions options_;
  Progress progress_;
  Clock::time_point start_ = Clock::now();
  std::string started_ = utc_timestamp(false);
  std::map<std::string, ManifestEntry> done_;
  std::unique_ptr<SetJournal> journal_;
  std::vector<std::shared_ptr<const Scene>> scenes_;
  std::vector<ManifestEntry> entries_;
  std::mutex entries_mutex_;
  size_t total_ = 0;
  std::atomic<size_t> finished_{0}, written_{0}, skipped_{0};
  std::atomic<double> render_seconds_{0}, prepare_seconds_{0}, compose_seconds_{0},
      encode_seconds_{0};
  GenerateReport report_;
};

void SetGenerator::prepare_folder() {
  check_writable(dir_);
  manifest_path_ = dir_ / manifest_name(options_.shard, options_.shards);
  journal_path_ = dir_ / journal_name(options_.shard, options_.shards);
  std::error_code ec;
  const bool has_manifest = fs::exists(manifest_path_, ec),
             has_journal = fs::exists(journal_path_, ec);
  if (!options_.resume && (has_manifest || has_journal))
    throw_input_error(dir_.string(),
                      "already holds a stimulus set (" +
                          (has_manifest ? manifest_path_ : journal_path_).filename().string() +
                          "); use --resume to finish it or choose a new folder");
  if (options_.resume)
    done_ = verified_earlier_images(dir_, journal_path_, manifest_path_,
                                    e_.sha256);  // refuses another experiment's set
}

// The temporary files an interrupted run of this part left: every one in a run of the whole set;
// in a shard only those of its own files, since other shards may be writing beside it.
void SetGenerator::remove_own_interrupted_writes(const std::vector<SetUnit>& units) const {
  if (options_.shards == 1) return remove_interrupted_writes(dir_);
  std::set<std::string> own;
  for (const SetUnit& u : units) {
    for (const std::string& file : files_of(u)) own.insert(file), own.insert("congruence/" + file);
    if (!u.is_reference() && u.frame >= 0) own.insert(mask_path(e_, u));
  }
  own.insert(manifest_path_.filename().string());
  remove_interrupted_writes(dir_, [&](const std::string& file) { return own.count(file) > 0; });
}

std::vector<SetUnit> SetGenerator::shard_units() const {
  std::vector<SetUnit> units;
  auto all = all_units(e_);
  for (size_t k = 0; k < all.size(); ++k)
    if (int(k % size_t(options_.shards)) == options_.shard - 1) units.push_back(all[k]);
  return units;
}

std::vector<std::string> SetGenerator::files_of(const SetUnit& u) const {
  std::vector<std::string> files;
  for (int l = 0; l < (u.is_reference() ? 1 : e_.lambda.count()); ++l)
    files.push_back(unit_path(e_, u, l));
  return files;
}

bool SetGenerator::all_done(const Shot& shot) const {
  for (const auto& u : shot)
    for (const std::string& file : files_of(u))
      if (!done_.count(file)) return false;
  return true;
}

void SetGenerator::record(ManifestEntry entry, bool is_new) {
  if (is_new) journal_->append(entry);
  {
    std::lock_guard<std::mutex> lock(entries_mutex_);
    entries_.push_back(std::move(entry));
  }
  ++(is_new ? written_ : skipped_);
  progress_.update(double(++finished_) / double(std::max<size_t>(total_, 1)));
}

// The display a reference was made for, so that the audit decodes the set as it will be shown: its
// encoding, a measured table's rows, and a calibrated display's luminance range.
void record_display(ManifestEntry& entry, const Display& display) {
  entry.extra["display_encoding"] = display.encoding.describe();
  if (display.encoding.kind() == DisplayEncoding::Kind::lut)
    entry.extra["display_lut"] = {{"codes", display.encoding.lut_codes()},
                                  {"luminances", display.encoding.lut_luminances()}};
  if (display.luminance_cd_m2)
    entry.extra["luminance_cd_m2"] = {{"black", display.luminance_cd_m2->first},
                                      {"white", display.luminance_cd_m2->second}};
}

// The display the experiment's headroom settled on: the scene's exposure and black level.
void record_headroom(const Scene& scene, ManifestEntry& entry) {
  entry.extra["exposure_stops"] = round_to(scene.display.exposure_stops, 4);
  entry.extra["black_level"] = round_to(scene.display.black_level, 6);
}

void SetGenerator::write_reference(const SetUnit& u, const View& view, const View* moved) {
  const std::string rel = reference_path(e_, u.scene, u.frame);
  if (done_.count(rel)) return record(done_.at(rel), false);
  auto te = Clock::now();
  ManifestEntry entry;
  entry.file = rel;
  entry.scene = e_.scenes[u.scene].name;
  entry.method = kReferenceMethod;
  if (u.frame >= 0) entry.frame = ManifestEntry::Frame{u.frame, e_.scenes[u.scene].fps};
  record_display(entry, view.scene->display);
  if (e_.headroom) record_headroom(*view.scene, entry);
  record_noise(entry, view, NoiseModel{}, view.display);
  if (e_.congruence)
    record_congruence(dir_, entry, view.display, view, e_.bits, e_.congruence_options);
  if (moved) record_coherence(entry, view, view_lightness(view), *moved, view_lightness(*moved));
  entry = write_stimulus(dir_, std::move(entry), view.display, e_.bits);
  encode_seconds_.fetch_add(since(te));
  record(std::move(entry), true);
}

std::unique_ptr<PreparedEnhancement> SetGenerator::prepare_for_grid(
    const ExperimentMethod& m, const SetUnit& u, const std::shared_ptr<const View>& view,
    size_t use) const {
  PrepareContext c = make_use_context(view, use, options_.jobs);
  c.compose_from_samples = true;  // a grid of λ
  return m.method->prepare(c, *m.parameters[u.sigma]);
}

void SetGenerator::write_condition(const SetUnit& u, const std::shared_ptr<const View>& view,
                                   const std::shared_ptr<const View>& moved,
                                   const std::vector<float>& plain, size_t use) {
  const ExperimentMethod& m = e_.methods[size_t(u.method)];
  auto tp = Clock::now();
  std::unique_ptr<PreparedEnhancement> prepared, prepared_moved;
  run_with_threads(options_.jobs, [&] {
    prepared = prepare_for_grid(m, u, view, use);
    if (moved) prepared_moved = prepare_for_grid(m, u, moved, use);
  });
  const nlohmann::json mask =
      options_.masks ? write_frame_mask(dir_, e_, u, *prepared, *view) : nlohmann::json();
  prepare_seconds_.fetch_add(since(tp));
  const nlohmann::json parameters = prepared->parameters();
  run_with_threads(options_.jobs, [&] {
    tbb::parallel_for(0, e_.lambda.count(), [&](int l) {
      const std::string rel = stimulus_path(e_, u, l);
      if (done_.count(rel)) return record(done_.at(rel), false);
      auto tc = Clock::now();
      Composed c = prepared->compose(e_.lambda.value(l));
      const double offset = e_.hold_mean ? hold_mean(*view, *prepared, e_.lambda.value(l), c) : 0.0;
      compose_seconds_.fetch_add(since(tc));
      auto te = Clock::now();
      ManifestEntry entry = stimulus_entry(e_, u, l, c, parameters);
      if (e_.hold_mean) entry.extra["mean_offset"] = round_to(offset, 4);
      if (!mask.is_null()) entry.extra["mask"] = mask;
      if (!e_.scenes[u.scene].probe_edges_x.empty())
        record_halo_widths(entry, *view, enhancement_layer(*view, c.display),
                           e_.scenes[u.scene].probe_edges_x);
      if (e_.headroom) record_headroom(*view->scene, entry);
      record_noise(entry, *view, prepared->noise(e_.lambda.value(l)), c.display);
      if (e_.congruence)
        record_congruence(dir_, entry, c.display, *view, e_.bits, e_.congruence_options);
      if (moved)
        record_coherence(
            entry, *view, enhancement_layer(*view, c.display), *moved,
            enhancement_layer(*moved, prepared_moved->compose(e_.lambda.value(l)).display), &plain);
      entry = write_stimulus(dir_, std::move(entry), c.display, e_.bits);
      encode_seconds_.fetch_add(since(te));
      record(std::move(entry), true);
    });
  });
}

void SetGenerator::make_shot(const Shot& shot, const ScenePlan& plan) {
  if (all_done(shot)) {  // skip the render
    for (const auto& u : shot)
      for (const std::string& file : files_of(u)) record(done_.at(file), false);
    return;
  }
  auto t0 = Clock::now();
  ViewOptions vo;
  vo.bits = e_.bits;
  vo.threads = options_.jobs;
  const SetUnit& first = shot.front();
  const std::shared_ptr<const Scene> base = scenes_[first.scene];
  const auto scene =
      first.frame < 0
          ? base
          : std::make_shared<const Scene>(scene_at(*base, base->animation->time_of(first.frame)));
  std::shared_ptr<const View> view, moved;
  run_with_threads(options_.jobs, [&] {
    view = e_.headroom ? headroom_view(first.scene, plan, vo) : render_view(scene, plan.plan, vo);
    moved = moved_view(e_, *view->scene, plan.plan, vo);
  });
  render_seconds_.fetch_add(since(t0));
  const std::vector<float> plain =
      plain_differences(*view, moved.get());  // once for every condition
  for (const auto& u : shot) {
    if (u.is_reference())
      write_reference(u, *view, moved.get());
    else
      write_condition(u, view, moved, plain, plan.use_of.at({u.method, int(u.sigma)}));
  }
}

// The still scene's view under the display change the experiment's headroom settles on. Each
// change the search tries is a render of its own; the last one is kept, since the search mostly
// settles on the change it tried last.
std::shared_ptr<const View> SetGenerator::headroom_view(size_t s, const ScenePlan& plan,
                                                        const ViewOptions& options) {
  const std::vector<double> extremes = {e_.lambda.value(0), e_.lambda.value(e_.lambda.count() - 1)};
  std::shared_ptr<const View> last;
  Headroom last_change;
  int renders = 0;
  auto at = [&](const Headroom& change) {
    auto scene = std::make_shared<Scene>(*scenes_[s]);
    scene->display.exposure_stops += change.exposure_stops;
    scene->display.black_level = std::min(0.5, scene->display.black_level + change.black_level);
    last_change = change;
    ++renders;
    return last = render_view(scene, plan.plan, options);
  };
  const Headroom change = find_headroom(
      [&](const Headroom& change) {
        return largest_clipped(at(change), extremes, options_.jobs, e_.hold_mean);
      },
      e_.max_clipped);
  if (last_change != change) at(change);
  // The search's renders are the set's slowest part; say what they settled on.
  std::fprintf(stderr,
               "stimuli %s: headroom for %s: exposure %+.2f stops, black level %.4f (%d renders)\n",
               e_.name.c_str(), e_.scenes[s].name.c_str(), last->scene->display.exposure_stops,
               last->scene->display.black_level, renders);
  return last;
}

void SetGenerator::finish() {
  Manifest manifest = manifest_header(e_);
  manifest.stimuli = std::move(entries_);
  auto run = [&] {
    report_.images_written = written_;
    report_.images_skipped = skipped_;
    report_.render_seconds = render_seconds_;
    report_.prepare_seconds = prepare_seconds_;
    report_.compose_seconds = compose_seconds_;
    report_.encode_seconds = encode_seconds_;
    report_.total_seconds = since(start_);
    return nlohmann::json{{"started_utc", started_},
                          {"finished_utc", utc_timestamp(false)},
                          {"jobs", options_.jobs},
                          {"seconds",
                           {{"render", report_.render_seconds},
                            {"prepare", report_.prepare_seconds},
                            {"compose", report_.compose_seconds},
                            {"encode", report_.encode_seconds},
                            {"total", report_.total_seconds}}}};
  };
  if (options_.shards > 1) {  // a part: its manifest only; the merge finishes the set
    sort_entries(manifest.stimuli);
    manifest.shard = std::make_pair(options_.shard, options_.shards);
    manifest.run = run();
    write_manifest(manifest_path_, manifest);
  } else {
    finish_set(
        e_, dir_, manifest, [&](size_t s) { return scenes_[s]; }, run, options_.jobs);
  }
  std::error_code ec;
  fs::remove(journal_path_, ec);
  report_.manifest = manifest_path_;
  progress_.finish("wrote " + manifest_path_.string() + " (" +
                   std::to_string(manifest.stimuli.size()) + " images, " +
                   format_seconds(report_.total_seconds) + ")");
}

GenerateReport SetGenerator::run() {
  prepare_folder();
  // Every scene is loaded (and so checked) before anything renders.
  for (size_t s = 0; s < e_.scenes.size(); ++s) scenes_.push_back(set_scene(e_, s));
  const std::vector<SetUnit> units = shard_units();
  if (options_.resume) remove_own_interrupted_writes(units);
  for (const auto& u : units) total_ += files_of(u).size();
  journal_ = std::make_unique<SetJournal>(journal_path_, e_.sha256);
  for (size_t s = 0; s < e_.scenes.size(); ++s) {
    const std::vector<Shot> shots = shots_of(s, units);
    if (shots.empty()) continue;
    const ScenePlan plan = scene_plan(e_, s);
    run_with_threads(options_.jobs, [&] {  // a sequence's frames in parallel
      tbb::parallel_for(size_t(0), shots.size(), [&](size_t k) { make_shot(shots[k], plan); });
    });
  }
  finish();
  return report_;
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

GenerateReport generate_stimulus_set(const Experiment& e, const fs::path& dir,
                                     const GenerateOptions& options) {
  return SetGenerator(e, dir, options).run();
}

fs::path merge_shard_manifests(const Experiment& e, const fs::path& dir, int jobs) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw_input_error(dir.string(), "no such folder (nothing to merge)");
  std::map<int, Manifest> shards;
  int count = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("manifest.shard-", 0) != 0) continue;
    Manifest m = read_manifest(entry.path());
    if (m.experiment_sha256 != e.sha256)
      throw_input_error(entry.path().string(), "was made from a different experiment file");
    if (!m.shard) throw_input_error(entry.path().string(), "shard: missing");
    if (count && m.shard->second != count)
      throw_input_error(entry.path().string(),
                        "belongs to a split into a different number of shards");
    count = m.shard->second;
    shards[m.shard->first] = std::move(m);
  }
  if (!count)
    throw_input_error(dir.string(), "no shard manifests (manifest.shard-I-of-N.json) to merge");
  std::string missing;
  for (int i = 1; i <= count; ++i)
    if (!shards.count(i)) missing += (missing.empty() ? "" : ",") + std::to_string(i);
  if (!missing.empty())
    throw_input_error(
        dir.string(),
        (missing.find(',') == std::string::npos
             ? "shard " + missing + " of " + std::to_string(count) + " has"
             : "shards " + missing + " of " + std::to_string(count) + " have") +
            " not finished (no manifest.shard-I-of-" + std::to_string(count) + ".json); run " +
            (missing.find(',') == std::string::npos ? "it" : "them") +
            " again (with Slurm: sbatch --array=" + missing + " " +
            (dir / "slurm" / "array.sbatch").string() + "), then merge; nothing was written");
  Manifest manifest = manifest_header(e);
  std::string started = "9999", finished = "0000";
  for (auto& [i, m] : shards) {
    manifest.stimuli.insert(manifest.stimuli.end(), m.stimuli.begin(), m.stimuli.end());
    started = std::min(started, m.run.value("started_utc", started));
    finished = std::max(finished, m.run.value("finished_utc", finished));
  }
  const nlohmann::json run = {
      {"started_utc", started}, {"finished_utc", finished}, {"merged_shards", count}};
  finish_set(
      e, dir, manifest, [&](size_t s) { return set_scene(e, s); }, [&] { return run; }, jobs);
  return dir / "manifest.json";
}

}  // namespace countershade
