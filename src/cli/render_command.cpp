// `countershade render`: one scene to one image, plus optional auxiliary buffers.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/method_options.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/image.h"
#include "core/progress.h"
#include "enhance/registry.h"
#include "enhance/stimulus_noise.h"
#include "enhance/view_plan.h"
#include "render/frame_range.h"
#include "render/ray_tracer.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "render/scene_animation.h"
#include "render/scene_loader.h"

namespace countershade::cli {
namespace {

namespace fs = std::filesystem;

std::string format_number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

struct RenderArgs {
  std::string scene;
  std::string output;
  MethodArgs method;
  std::optional<int> width, height, spp, threads;
  std::optional<long long> seed;
  std::optional<double> exposure, black_level, noise;
  int bits = 8;
  std::string aux;
  std::string frames;     // "A:B": frames of the scene's animation
  std::string reference;  // also the plain image, from the same render
};

// Writes the G-buffer and the sampling as EXR files a researcher can open: depth, normal, object
// id, samples per pixel and the estimated L* noise of the unenhanced image per pixel.
void write_aux(const fs::path& dir, const RenderResult& r) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw_input_error(dir.string(), "cannot create folder (" + ec.message() + ")");
  const GBuffer& g = r.gbuffer;
  Image depth(g.width, g.height, 1), normal(g.width, g.height, 3), object(g.width, g.height, 1);
  Image spp(g.width, g.height, 1), noise(g.width, g.height, 1);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      size_t i = g.index(x, y);
      depth.at(x, y) = g.depth[i];
      for (int c = 0; c < 3; ++c) normal.at(x, y, c) = g.normal[i][c];
      object.at(x, y) = float(g.object[i]);
      spp.at(x, y) = float(r.spp[i]);
      noise.at(x, y) = r.noise[i];
    }
  write_image(dir / "depth.exr", depth);
  write_image(dir / "normal.exr", normal);
  write_image(dir / "object_id.exr", object);
  write_image(dir / "spp.exr", spp);
  write_image(dir / "noise.exr", noise);
}

// The output's format, checked before any work.
std::string check_output(const RenderArgs& args, bool enhanced) {
  const std::string ext = check_output_file(args.output, {".png", ".tif", ".tiff", ".exr"},
                                            ".png, .tif (display-encoded) or .exr (linear)");
  if (ext == ".exr" && enhanced)
    throw_input_error(args.output, "enhanced stimuli are display-referred: write .png or .tif");
  if (!args.aux.empty()) check_output_folder(args.aux);
  if (!args.reference.empty())
    check_output_file(args.reference, {".png", ".tif", ".tiff"}, ".png or .tif");
  return ext;
}

std::shared_ptr<Scene> load_render_scene(const RenderArgs& args, const RenderRequest& request) {
  // Only methods that work on the scene's surfaces need its surface graphs (a refinement rebuilds
  // them).
  auto scene =
      std::make_shared<Scene>(load_scene(args.scene, request.scene && !request.refine_edge_length));
  apply_request(*scene, request);
  resize(scene->camera, args.width, args.height);
  if (args.spp) scene->settings.spp = *args.spp;
  if (args.noise) {
    if (scene->settings.sampling == SamplingMode::independent)
      throw_input_error(args.scene,
                        "render.sampler: the independent sampler takes a fixed spp, not --noise");
    scene->settings.spp.reset();
    scene->settings.noise.target = *args.noise;
    scene->settings.noise.p99 = std::max(scene->settings.noise.p99, 4 * *args.noise);
  }
  if (args.seed) scene->settings.seed = uint64_t(*args.seed);
  if (args.exposure) scene->display.exposure_stops = *args.exposure;
  if (args.black_level) scene->display.black_level = *args.black_level;
  return scene;
}

// The method's parameters on the summary line. An array or object of more than kShown items
// (usm3d's iterations per object, lla's smoothing counts per component: hundreds in a cluttered
// scene) shows its first items and how many follow (a set's manifest records them in full).
void append_brief(std::string& out, const nlohmann::json& j) {
  constexpr size_t kShown = 8;
  if (!j.is_array() && !j.is_object()) {
    out += j.dump();
    return;
  }
  out += j.is_array() ? '[' : '{';
  size_t shown = 0;
  for (auto it = j.begin(); it != j.end() && shown < kShown; ++it, ++shown) {
    if (shown > 0) out += ',';
    if (j.is_object()) out += nlohmann::json(it.key()).dump() + ':';
    append_brief(out, it.value());
  }
  if (j.size() > kShown) out += ",… " + std::to_string(j.size() - kShown) + " more";
  out += j.is_array() ? ']' : '}';
}

std::string brief(const nlohmann::json& j) {
  std::string out;
  append_brief(out, j);
  return out;
}

// "wrote out.png (512x384, spp 16/41.3/1024, noise 0.31 L* RMS, p99 0.92, 12.1 s, 3.2 M rays/s)".
std::string render_summary(const std::string& output, const View& view, const NoiseSummary& noise,
                           double seconds) {
  const RenderResult& r = view.render;
  const SampleCounts& spp = r.sampling.pixels;
  char text[320];
  std::snprintf(
      text, sizeof text,
      "wrote %s (%dx%d, spp %u/%.1f/%u min/mean/max, noise %.2f L* RMS, p99 %.2f%s, %s, %.2f M "
      "rays/s",
      output.c_str(), view.width(), view.height(), spp.min, spp.mean, spp.max, noise.rms, noise.p99,
      r.sampling.stopped_by.empty() ? "" : (", stopped by " + r.sampling.stopped_by).c_str(),
      format_seconds(seconds).c_str(), double(r.rays.primary + r.rays.shadow) / seconds * 1e-6);
  std::string out = text;
  if (!r.vertices.front.empty()) {
    std::snprintf(text, sizeof text, "; vertex signal %.1f samples per point, %s",
                  r.vertices.samples.mean, format_seconds(r.vertices.seconds).c_str());
    out += text;
  }
  return out + ")";
}

// Renders `scene` (enhanced as asked) to `output`; returns the summary line.
std::string render_one(const RenderArgs& args, const ResolvedMethod& method,
                       std::shared_ptr<const Scene> scene, const std::string& output,
                       const std::string& reference, const std::string& ext, Progress& progress) {
  auto start = std::chrono::steady_clock::now();
  ViewOptions vo;
  vo.bits = args.bits;
  vo.threads = args.threads.value_or(0);
  vo.progress = [&](double f) { progress.update(f); };
  ViewPlan plan;
  plan.uses.push_back({method.method, method.parameters, nlohmann::json::object()});
  plan.max_abs_lambda = std::abs(args.method.lambda);
  std::shared_ptr<const View> view = render_view(scene, plan, vo);
  if (!args.aux.empty()) write_aux(args.aux, view->render);
  // The plain image of the very samples the stimulus is composed from: two renders would sample
  // silhouettes differently under the adaptive budget.
  if (!reference.empty()) write_image(reference, view->display, {args.bits});

  std::string details;
  NoiseSummary noise = summarize_noise(view->render.noise);
  if (ext == ".exr") {
    write_image(output, view->render.radiance);
  } else {
    auto prepared =
        method.method->prepare(make_use_context(view, 0, vo.threads), *method.parameters);
    Composed stimulus = prepared->compose(args.method.lambda);
    write_image(output, stimulus.display, {args.bits});
    noise = summarize_noise(
        stimulus_noise(*view, prepared->noise(args.method.lambda), stimulus.display));
    if (!args.aux.empty()) write_auxiliary(args.aux, *prepared);
    if (method.method->enhances())
      details = ", " + method.method->name() + " λ=" + format_number(args.method.lambda) + ", " +
                std::to_string(stimulus.clipped_pixels) + " clipped pixels, " +
                brief(prepared->parameters());
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return render_summary(output, *view, noise, seconds) + details;
}

// OUT.png → OUT-0007.png for frame 7.
std::string frame_path(const std::string& output, int frame) {
  const std::filesystem::path p(output);
  char number[16];
  std::snprintf(number, sizeof number, "-%04d", frame);
  return (p.parent_path() / (p.stem().string() + number + p.extension().string())).string();
}

void run(const RenderArgs& args, const CLI::App* cmd) {
  const ResolvedMethod method = resolve_method(cmd, args.method);
  const std::string ext = check_output(args, method.method->enhances());
  std::shared_ptr<const Scene> scene = load_render_scene(args, method.request);
  method.method->check_scene(*scene, *method.parameters);
  if (args.frames.empty()) {
    Progress progress("render");
    progress.finish(render_one(args, method, scene, args.output, args.reference, ext, progress));
    return;
  }
  if (!args.aux.empty())
    throw InputError("--aux: not with --frames (render one frame with its own --aux)");
  const auto [first, last] = frame_range(args.frames, *scene, 0, "--frames");
  for (int f = first; f <= last; ++f) {
    Progress progress("render frame " + std::to_string(f));
    auto posed = std::make_shared<const Scene>(scene_at(*scene, scene->animation->time_of(f)));
    const std::string reference = args.reference.empty() ? "" : frame_path(args.reference, f);
    progress.finish(
        render_one(args, method, posed, frame_path(args.output, f), reference, ext, progress));
  }
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene description to an image.");
  cmd->add_option("scene", args->scene, "Scene description (JSON, see docs/scene-format.md)")
      ->required();
  cmd->add_option("-o,--output", args->output,
                  "Output image: .png/.tif display-encoded, .exr linear radiance")
      ->required();
  add_method_options(cmd, args->method, "Enhancement method (`countershade methods` lists them)");
  cmd->add_option("--width", args->width,
                  "Override the camera's width in pixels (alone: the height follows the scene's "
                  "aspect ratio)")
      ->check(CLI::Range(1, 16384));
  cmd->add_option("--height", args->height,
                  "Override the camera's height in pixels (alone: the width follows the scene's "
                  "aspect ratio)")
      ->check(CLI::Range(1, 16384));
  auto* spp = cmd->add_option("--spp", args->spp,
                              "A fixed number of samples per pixel instead of the noise budget")
                  ->check(CLI::Range(1, 65536));
  cmd->add_option("--noise", args->noise,
                  "Sample to this L* noise RMS of the written image (the scene's budget otherwise)")
      ->check(CLI::Range(0.01, 100.0))
      ->excludes(spp);
  cmd->add_option("--seed", args->seed, "Random seed; the same seed gives byte-identical output")
      ->check(CLI::Range(0ll, 1ll << 53));
  cmd->add_option("--exposure", args->exposure, "Override the exposure in stops")
      ->check(CLI::Range(-30.0, 30.0));
  cmd->add_option("--black-level", args->black_level,
                  "Override the display's black level (share of full scale)")
      ->check(CLI::Range(0.0, 0.5));
  cmd->add_option("--bits", args->bits, "PNG/TIFF bit depth")
      ->check(CLI::IsMember({8, 16}))
      ->capture_default_str();
  cmd->add_option(
      "--frames", args->frames,
      "Render frames A:B of the scene's animation, numbered into OUT (OUT-0000.png, ...)");
  cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option(
      "--aux", args->aux,
      "Also write depth.exr, normal.exr, object_id.exr, spp.exr, noise.exr (L* per pixel) and the "
      "method's intermediate images "
      "(e.g. depth-usm's D, G*D and ΔD) to this folder");
  cmd->add_option("--reference", args->reference,
                  "Also write the plain image (.png/.tif) from the same samples as the enhanced "
                  "one (with --frames, "
                  "numbered like OUT)");
  cmd->callback([args, cmd] { run(*args, cmd); });
  cmd->footer(method_parameters_help() +
              "\nExamples:\n"
              "  countershade render experiments/scenes/clutter.json -o clutter.png\n"
              "  countershade render experiments/scenes/cornsweet-cube.json -o cube.png --method "
              "usm3d --lambda 1.5 "
              "--sigma-fraction 0.05\n"
              "  countershade render experiments/scenes/clutter.json -o dark.png --method "
              "depth-usm --operator darken "
              "--lambda 0.8 --kernel 5%");
}

}  // namespace countershade::cli
