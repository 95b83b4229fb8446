// `countershade flicker`: the flicker of an enhancement over an animated scene's frames
// (stimuli/flicker.h measures it; this command reads its options and writes its CSV, maps and
// summary).

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/method_options.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/false_colour.h"
#include "core/progress.h"
#include "enhance/view_plan.h"
#include "measures/flicker.h"
#include "measures/flicker_table.h"
#include "render/frame_range.h"
#include "render/scene_loader.h"

namespace countershade::cli {
namespace {

struct FlickerArgs {
  std::string scene, frames, csv, maps, object, without, on, near, component = "layer";
  MethodArgs method;
  std::optional<int> width, height, spp, threads;
  int bits = 8;
  FlickerOptions options;
};

// |ΔE| per pixel in false colour, 0 … 5 L* (NaN, where a pixel did not count: black).
void write_map(const std::string& dir, const char* prefix, int frame,
               const std::vector<float>& differences, const View& view) {
  Image values(view.width(), view.height(), 1);
  for (size_t i = 0; i < differences.size(); ++i) values.pixels[i] = differences[i] / 5.0f;
  char name[32];
  std::snprintf(name, sizeof name, "%s-%04d.png", prefix, frame);
  write_image(std::filesystem::path(dir) / name, false_colour_image(values));
}

void run(FlickerArgs& args, const CLI::App* cmd) {
  const ResolvedMethod m = resolve_method(cmd, args.method);
  if (!args.csv.empty()) check_output_file(args.csv, {".csv"}, ".csv");
  if (!args.maps.empty())
    check_output_folder(args.maps), std::filesystem::create_directories(args.maps);
  Scene base = load_scene(args.scene);
  apply_request(base, m.request);
  resize(base.camera, args.width, args.height);
  if (args.spp) base.settings.spp = *args.spp;
  m.method->check_scene(base, *m.parameters);
  const auto [first, last] = frame_range(args.frames, base, 1, "--frames");
  // With --without, the scene as it was keeps the object that --near's region is measured around.
  std::optional<Scene> whole;
  if (!args.without.empty()) whole = base, remove_object(base, args.without);
  const Scene& full = whole ? *whole : base;
  args.options.object = named_object(base, args.object, "--object");
  args.options.on = named_object(full, args.on, "--on");
  args.options.near = named_object(full, args.near, "--near");
  if (whole && args.options.has_region()) args.options.region_scene = &*whole;
  FlickerTable table(args.options);
  Progress progress("flicker");
  FlickerRender render{m.method, m.parameters, args.method.lambda, args.bits,
                       args.threads.value_or(0)};
  if (args.component == "mask") render.component = FlickerComponent::mask;
  measure_rendered_flicker(
      base, first, last, render, args.options,
      [&](int frame, const FlickerFrame& a, const FlickerFrame&, const PlainChange& plain,
          const PairFlicker& pair) {
        if (!args.maps.empty()) write_map(args.maps, "flicker", frame, pair.differences, *a.view);
        if (!args.maps.empty()) write_map(args.maps, "plain", frame, plain.differences, *a.view);
        table.add(frame, plain, pair);
      },
      [&](double done) { progress.update(done); });
  if (table.pixels() == 0)  // an RMS over nothing would read as perfect coherence
    throw InputError(
        args.scene +
        ": no surface point is seen in two consecutive frames, so there is no flicker to measure");
  if (!args.csv.empty()) write_text_atomically(args.csv, table.csv());
  progress.finish(table.summary(args.object, args.component));
}

// The measures beyond the layer's RMS (FlickerOptions).
void add_measure_options(CLI::App* cmd, FlickerArgs& args) {
  cmd->add_option("--object", args.object,
                  "Also report how much the enhancement of this object's pixels changes per pair "
                  "(largest and 99th percentile over its pixels seen in both frames, in levels of "
                  "8-bit output; CSV "
                  "columns object_*, and object_stable_* over its stable pixels with --stable)");
  cmd->add_option(
         "--scale-px", args.options.scale_px,
         "Also compare the layers blurred with a Gaussian of this σ in pixels: the change at the "
         "enhancement's scale rather than the pixel's (CSV columns *_at_scale_lstar)")
      ->check(CLI::Range(0.0, 256.0));
  cmd->add_option(
         "--stable", args.options.stable,
         "Also the flicker over the pixels where the plain L* reprojects within this many L*: "
         "surface that "
         "neither a change of the scene (a moving shadow) nor the resampling disturbs (CSV columns "
         "flicker_stable_lstar, stable_pixels)")
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--on", args.on,
                  "Also the RMS over this object's pixels (of the earlier frame of each pair); "
                  "with --near, only those "
                  "near that object (CSV columns region_lstar, plain_region_lstar, region_pixels)");
  cmd->add_option(
      "--near", args.near,
      "Also the RMS over the pixels within --within pixels of this object's (itself excluded)");
  cmd->add_option("--within", args.options.within_px, "The distance for --near, in pixels")
      ->check(CLI::Range(1.0, 4096.0))
      ->capture_default_str();
}

}  // namespace

void add_flicker_command(CLI::App& app) {
  auto args = std::make_shared<FlickerArgs>();
  CLI::App* cmd = app.add_subcommand("flicker",
                                     "Measure how an enhancement changes between the frames of an "
                                     "animated scene, in L* per frame.");
  cmd->add_option("scene", args->scene,
                  "Scene description with an animation (docs/scene-format.md)")
      ->required();
  add_method_options(cmd, args->method, "Enhancement method");
  cmd->add_option("--component", args->component,
                  "What is measured: the enhancement's layer (enhanced − plain L*), or the "
                  "method's mask, the low-pass "
                  "signal M of U = S + λ(S − M) (depth-usm: 100·ΔD; docs/enhancement-methods.md, "
                  "\"Mask flicker\")")
      ->check(CLI::IsMember({"layer", "mask"}))
      ->capture_default_str();
  cmd->add_option("--frames", args->frames, "Frames A:B (default: all)");
  cmd->add_option(
      "--csv", args->csv,
      "Write frame, flicker, the plain render's reprojection error and pixels per pair");
  cmd->add_option(
      "--maps", args->maps,
      "Write |change| per pixel of each pair as DIR/flicker-NNNN.png, and the plain L*'s as "
      "DIR/plain-NNNN.png (viridis over 0–5 L*; black: not counted)");
  cmd->add_option("--without", args->without,
                  "Leave this object out of the scene, with its motion (e.g. a moving occluder, to "
                  "see the flicker "
                  "of the camera's motion alone)");
  add_measure_options(cmd, *args);
  cmd->add_option("--bits", args->bits, "The stimuli's bit depth (8 or 16), as a set's \"bits\"")
      ->check(CLI::IsMember({8, 16}))
      ->capture_default_str();
  cmd->add_option(
         "--width", args->width,
         "Override the camera's width in pixels (alone: the height follows the aspect ratio)")
      ->check(CLI::Range(1, 16384));
  cmd->add_option(
         "--height", args->height,
         "Override the camera's height in pixels (alone: the width follows the aspect ratio)")
      ->check(CLI::Range(1, 16384));
  cmd->add_option("--spp", args->spp,
                  "A fixed number of samples per pixel instead of the noise budget")
      ->check(CLI::Range(1, 65536));
  cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  cmd->callback([cmd, args] { run(*args, cmd); });
  cmd->footer(
      method_parameters_help() +
      "\nExample:\n"
      "  countershade flicker orbit.json --method usm2d --sigma-px 3 --lambda 1 --csv usm2d.csv\n"
      "  countershade flicker occluder.json --method usm3d --sigma 0.05 --component mask --on "
      "floor --near stick");
}

}  // namespace countershade::cli
