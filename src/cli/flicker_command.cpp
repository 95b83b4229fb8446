// `countershade flicker`: how much an enhancement changes from frame to frame of an animated
// scene at the surface points both frames see (docs/enhancement-methods.md, "Flicker").

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>

#include "cli/commands.h"
#include "render/frame_range.h"
#include "cli/method_options.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/false_colour.h"
#include "core/gaussian.h"
#include "core/image.h"
#include "core/progress.h"
#include "enhance/lightness.h"
#include "render/scene_animation.h"
#include "stimuli/perspective_coherence.h"

namespace countershade::cli {
namespace {

struct FlickerArgs {
  std::string scene, frames, csv, maps, object, without;
  MethodArgs method;
  std::optional<int> width, height, spp, threads;
  int bits = 8;  // the stimuli's output bit depth
  double scale_px = 0;  // > 0: also compare the layers blurred to this scale
  double stable = 0;    // > 0: also the flicker where the plain L* reprojects within this
};

struct Frame {
  std::shared_ptr<const View> view;
  std::vector<float> layer, plain;  // enhanced − plain L*, and plain L*
  std::array<std::vector<float>, 3> levels;  // enhanced − plain per channel, in code levels
  std::vector<float> layer_at_scale, plain_at_scale;  // both blurred (--scale-px)
};

std::vector<float> blurred(const std::vector<float>& values, const View& view, double sigma) {
  std::vector<float> out(values.size());
  gaussian_blur(values.data(), out.data(), view.width(), view.height(), sigma);
  return out;
}

// The enhancement layer of each channel in levels of 8-bit output (whatever the bit depth: the
// unit the occluder bound is stated in).
std::array<std::vector<float>, 3> level_layers(const View& view, const Image& enhanced) {
  const float scale = 255.0f;
  std::array<std::vector<float>, 3> out;
  for (int c = 0; c < 3; ++c) {
    out[size_t(c)].resize(size_t(view.width()) * size_t(view.height()));
    for (size_t i = 0; i < out[size_t(c)].size(); ++i)
      out[size_t(c)][i] = scale * (enhanced.pixels[3 * i + size_t(c)] - view.display.pixels[3 * i + size_t(c)]);
  }
  return out;
}

Frame render_frame(const Scene& base, int frame, const ResolvedMethod& m, const FlickerArgs& args) {
  auto scene = std::make_shared<const Scene>(scene_at(base, base.animation->time_of(frame)));
  ViewPlan plan;
  plan.uses.push_back({m.method, m.parameters, nlohmann::json::object()});
  plan.max_abs_lambda = std::abs(args.method.lambda);
  ViewOptions options;
  options.threads = args.threads.value_or(0);
  options.bits = args.bits;
  Frame f;
  f.view = render_view(scene, plan, options);
  const auto prepared = m.method->prepare(make_use_context(f.view, 0, options.threads), *m.parameters);
  const Image enhanced = prepared->compose(args.method.lambda).display;
  f.layer = enhancement_layer(*f.view, enhanced);
  f.plain = view_lightness(*f.view);
  if (!args.object.empty()) f.levels = level_layers(*f.view, enhanced);
  if (args.scale_px > 0) {
    f.layer_at_scale = blurred(f.layer, *f.view, args.scale_px);
    f.plain_at_scale = blurred(f.plain, *f.view, args.scale_px);
  }
  return f;
}

// |ΔE| per pixel in false colour, 0 … 5 L* (NaN, where a pixel did not count: black).
void write_map(const std::string& dir, const char* prefix, int frame, const std::vector<float>& differences,
               const View& view) {
  Image values(view.width(), view.height(), 1);
  for (size_t i = 0; i < differences.size(); ++i) values.pixels[i] = differences[i] / 5.0f;
  char name[32];
  std::snprintf(name, sizeof name, "%s-%04d.png", prefix, frame);
  write_image(std::filesystem::path(dir) / name, false_colour_image(values));
}

// How much the enhancement of one object's pixels changes between two frames, in levels of 8-bit
// output (at any bit depth): per pixel the largest change over the three channels.
struct ObjectChange {
  double max = 0, p99 = 0;
  size_t pixels = 0;
};

// One frame pair's per-pixel changes (NaN where a pixel did not count): of the layer and of the
// plain L*, with their RMS.
struct PairChanges {
  Reprojection layer, plain;
  std::vector<float> layer_differences, plain_differences;
};

PairChanges pair_changes(const Frame& a, const Frame& b, const CarryPoint& carry) {
  PairChanges out;
  out.layer = reprojection_rms(*a.view, a.layer, *b.view, b.layer, carry, &out.layer_differences);
  out.plain = reprojection_rms(*a.view, a.plain, *b.view, b.plain, carry, &out.plain_differences);
  return out;
}

// Per pixel of the object seen in both frames, the largest change over the three channels (−1
// elsewhere).
std::vector<float> object_largest_change(const Frame& a, const Frame& b, const CarryPoint& carry, int object) {
  std::vector<float> largest(a.layer.size(), -1.0f);
  for (size_t c = 0; c < 3; ++c) {
    std::vector<float> differences;
    reprojection_rms(*a.view, a.levels[c], *b.view, b.levels[c], carry, &differences);
    for (size_t i = 0; i < differences.size(); ++i)
      if (a.view->object_at(i) == object && !std::isnan(differences[i]))
        largest[i] = std::max(largest[i], differences[i]);
  }
  return largest;
}

// The largest change and its 99th percentile over the object's pixels; with `stable`, only over
// those whose plain L* changes by at most that much.
ObjectChange object_change(const std::vector<float>& largest, const std::vector<float>& plain_differences,
                           std::optional<double> stable) {
  std::vector<float> values;
  for (size_t i = 0; i < largest.size(); ++i)
    if (largest[i] >= 0 && (!stable || plain_differences[i] <= *stable)) values.push_back(largest[i]);
  ObjectChange out;
  out.pixels = values.size();
  if (values.empty()) return out;
  std::sort(values.begin(), values.end());
  out.max = values.back();
  out.p99 = values[size_t(0.99 * double(values.size() - 1))];
  return out;
}

struct Totals {
  double flicker = 0, plain = 0, at_scale = 0, plain_at_scale = 0, stable = 0, stable_share = 0;
  ObjectChange object, object_stable;  // the worst pair's
  int pairs = 0;
  size_t pixels = 0;  // over every pair
};

void add_object_change(const ObjectChange& change, std::ostringstream& row, ObjectChange& worst) {
  row << ',' << change.max << ',' << change.p99 << ',' << change.pixels;
  worst.max = std::max(worst.max, change.max);
  worst.p99 = std::max(worst.p99, change.p99);
}

// The optional measures of a pair: at a scale, over stable pixels, of one object.
void add_options(const Frame& a, const Frame& b, const CarryPoint& carry, const PairChanges& changes,
                 const FlickerArgs& args, int object, std::ostringstream& row, Totals& totals) {
  if (args.scale_px > 0) {
    const double layer = reprojection_rms(*a.view, a.layer_at_scale, *b.view, b.layer_at_scale, carry).rms;
    const double own = reprojection_rms(*a.view, a.plain_at_scale, *b.view, b.plain_at_scale, carry).rms;
    row << ',' << layer << ',' << own;
    totals.at_scale += layer;
    totals.plain_at_scale += own;
  }
  if (args.stable > 0) {
    const Reprojection stable = rms_where_stable(changes.layer_differences, changes.plain_differences, args.stable);
    row << ',' << stable.rms << ',' << stable.pixels;
    totals.stable += stable.rms;
    totals.stable_share += changes.layer.pixels ? double(stable.pixels) / double(changes.layer.pixels) : 0.0;
  }
  if (object < 0) return;
  const std::vector<float> largest = object_largest_change(a, b, carry, object);
  add_object_change(object_change(largest, changes.plain_differences, std::nullopt), row, totals.object);
  if (args.stable > 0)
    add_object_change(object_change(largest, changes.plain_differences, args.stable), row, totals.object_stable);
}

// One frame pair's CSV row, added to the totals.
std::string pair_row(const Scene& base, const Frame& a, const Frame& b, int frame, const FlickerArgs& args, int object,
                     Totals& totals) {
  const CarryPoint carry = carry_between_frames(base, frame - 1, frame);
  const PairChanges changes = pair_changes(a, b, carry);
  if (!args.maps.empty()) {
    write_map(args.maps, "flicker", frame, changes.layer_differences, *a.view);
    write_map(args.maps, "plain", frame, changes.plain_differences, *a.view);
  }
  std::ostringstream row;
  row << frame << ',' << changes.layer.rms << ',' << changes.plain.rms << ',' << changes.layer.pixels;
  totals.flicker += changes.layer.rms;
  totals.plain += changes.plain.rms;
  ++totals.pairs;
  totals.pixels += changes.layer.pixels;
  add_options(a, b, carry, changes, args, object, row, totals);
  row << '\n';
  return row.str();
}

// The index of the object an option names (-1 without one).
int named_object(const Scene& scene, const std::string& name, const char* option) {
  if (name.empty()) return -1;
  for (size_t k = 0; k < scene.objects.size(); ++k)
    if (scene.objects[k].name == name) return int(k);
  throw InputError(std::string(option) + ": " + scene.file.string() + " has no object called '" + name + "'");
}

// The scene without the object --without names, and without its motion: the flicker that remains
// when, say, a moving occluder is taken out.
void remove_object(Scene& scene, const std::string& name) {
  const int k = named_object(scene, name, "--without");
  scene.objects.erase(scene.objects.begin() + k);
  auto& paths = scene.animation->objects;
  std::erase_if(paths, [k](const ObjectPath& p) { return p.object == size_t(k); });
  for (ObjectPath& p : paths)
    if (p.object > size_t(k)) --p.object;
}

std::string summary(const Totals& t, const FlickerArgs& args) {
  const std::string& object = args.object;
  char line[320];
  std::snprintf(line, sizeof line, "%d frame pairs, mean flicker %.4f L* (the plain render's own reprojection %.4f L*)",
                t.pairs, t.flicker / t.pairs, t.plain / t.pairs);
  std::string out = line;
  if (args.scale_px > 0) {
    std::snprintf(line, sizeof line, "; at %g px: %.4f L* (plain %.4f L*)", args.scale_px, t.at_scale / t.pairs,
                  t.plain_at_scale / t.pairs);
    out += line;
  }
  if (args.stable > 0) {
    std::snprintf(line, sizeof line, "; where the plain L* reprojects within %g: %.4f L* (%.0f %% of the pixels)",
                  args.stable, t.stable / t.pairs, 100.0 * t.stable_share / t.pairs);
    out += line;
  }
  if (!object.empty()) {
    std::snprintf(line, sizeof line, "; %s: largest change %.2f code levels (p99 %.2f, worst pair)", object.c_str(),
                  t.object.max, t.object.p99);
    out += line;
    if (args.stable > 0) {
      std::snprintf(line, sizeof line, ", where stable %.2f (p99 %.2f)", t.object_stable.max, t.object_stable.p99);
      out += line;
    }
  }
  return out;
}

void run(const FlickerArgs& args, const CLI::App* cmd) {
  const ResolvedMethod m = resolve_method(cmd, args.method);
  if (!args.csv.empty()) check_output_file(args.csv, {".csv"}, ".csv");
  if (!args.maps.empty()) {
    check_output_folder(args.maps);
    std::filesystem::create_directories(args.maps);
  }
  Scene base = load_scene(args.scene);
  apply_request(base, m.request);
  resize(base.camera, args.width, args.height);
  if (args.spp) base.settings.spp = *args.spp;
  m.method->check_scene(base, *m.parameters);
  const auto [first, last] = frame_range(args.frames, base, 1, "--frames");
  if (!args.without.empty()) remove_object(base, args.without);
  const int object = named_object(base, args.object, "--object");
  std::string csv = "frame,flicker_lstar,plain_reprojection_lstar,pixels";
  if (args.scale_px > 0) csv += ",flicker_at_scale_lstar,plain_at_scale_lstar";
  if (args.stable > 0) csv += ",flicker_stable_lstar,stable_pixels";
  if (object >= 0) csv += ",object_max_levels,object_p99_levels,object_pixels";
  if (object >= 0 && args.stable > 0) csv += ",object_stable_max_levels,object_stable_p99_levels,object_stable_pixels";
  csv += '\n';
  Progress progress("flicker");
  Totals totals;
  Frame previous = render_frame(base, first, m, args);
  for (int f = first + 1; f <= last; ++f) {
    Frame current = render_frame(base, f, m, args);
    csv += pair_row(base, previous, current, f, args, object, totals);
    previous = std::move(current);
    progress.update(double(f - first) / double(last - first));
  }
  if (totals.pixels == 0)  // an RMS over nothing would read as perfect coherence
    throw InputError(args.scene + ": no surface point is seen in two consecutive frames, so there is no flicker to measure");
  if (!args.csv.empty()) write_text_atomically(args.csv, csv);
  progress.finish(summary(totals, args));
}

}  // namespace

void add_flicker_command(CLI::App& app) {
  auto args = std::make_shared<FlickerArgs>();
  CLI::App* cmd = app.add_subcommand(
      "flicker", "Measure how an enhancement changes between the frames of an animated scene, in L* per frame.");
  cmd->add_option("scene", args->scene, "Scene description with an animation (docs/scene-format.md)")->required();
  add_method_options(cmd, args->method, "Enhancement method");
  cmd->add_option("--frames", args->frames, "Frames A:B (default: all)");
  cmd->add_option("--csv", args->csv, "Write frame, flicker, the plain render's reprojection error and pixels per pair");
  cmd->add_option("--maps", args->maps,
                  "Write |change| per pixel of each pair as DIR/flicker-NNNN.png, and the plain L*'s as "
                  "DIR/plain-NNNN.png (viridis over 0–5 L*; black: not counted)");
  cmd->add_option("--without", args->without,
                  "Leave this object out of the scene, with its motion (e.g. a moving occluder, to see the flicker "
                  "of the camera's motion alone)");
  cmd->add_option("--object", args->object,
                  "Also report how much the enhancement of this object's pixels changes per pair "
                  "(largest and 99th percentile over its pixels seen in both frames, in levels of 8-bit output; CSV "
                  "columns object_*, and object_stable_* over its stable pixels with --stable)");
  cmd->add_option("--scale-px", args->scale_px,
                  "Also compare the layers blurred with a Gaussian of this σ in pixels: the change at the "
                  "enhancement's scale rather than the pixel's (CSV columns *_at_scale_lstar)")
      ->check(CLI::Range(0.0, 256.0));
  cmd->add_option("--stable", args->stable,
                  "Also the flicker over the pixels where the plain L* reprojects within this many L*: surface that "
                  "neither a change of the scene (a moving shadow) nor the resampling disturbs (CSV columns "
                  "flicker_stable_lstar, stable_pixels)")
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--bits", args->bits, "The stimuli's bit depth (8 or 16), as a set's \"bits\"")
      ->check(CLI::IsMember({8, 16}))
      ->capture_default_str();
  cmd->add_option("--width", args->width, "Override the camera's width in pixels (alone: the height follows the aspect ratio)")
      ->check(CLI::Range(1, 16384));
  cmd->add_option("--height", args->height, "Override the camera's height in pixels (alone: the width follows the aspect ratio)")
      ->check(CLI::Range(1, 16384));
  cmd->add_option("--spp", args->spp, "A fixed number of samples per pixel instead of the noise budget")->check(CLI::Range(1, 65536));
  cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 1024));
  cmd->callback([cmd, args] { run(*args, cmd); });
  cmd->footer(method_parameters_help() +
              "\nExample:\n"
              "  countershade flicker orbit.json --method usm2d --sigma-px 3 --lambda 1 --csv usm2d.csv");
}

}  // namespace countershade::cli
