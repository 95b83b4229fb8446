// `countershade render`: one scene to one image, plus optional auxiliary buffers.

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "core/error.h"
#include "core/image.h"
#include "core/progress.h"
#include "cli/method_options.h"
#include "core/atomic_file.h"
#include "enhance/method.h"
#include "render/ray_tracer.h"
#include "render/renderer.h"
#include "render/scene.h"

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
  std::optional<double> exposure;
  int bits = 8;
  std::string aux;
  int ring_samples = 3;
  std::optional<double> refine;
};

// Writes the G-buffer as EXR files a researcher can open: depth, normal, object id.
void write_aux(const fs::path& dir, const GBuffer& g) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw_input_error(dir.string(), "cannot create folder (" + ec.message() + ")");
  Image depth(g.width, g.height, 1), normal(g.width, g.height, 3), object(g.width, g.height, 1);
  for (int y = 0; y < g.height; ++y)
    for (int x = 0; x < g.width; ++x) {
      size_t i = g.index(x, y);
      depth.at(x, y) = g.depth[i];
      for (int c = 0; c < 3; ++c) normal.at(x, y, c) = g.normal[i][c];
      object.at(x, y) = float(g.object[i]);
    }
  write_image(dir / "depth.exr", depth);
  write_image(dir / "normal.exr", normal);
  write_image(dir / "object_id.exr", object);
}

void run(RenderArgs args) {
  fs::path output(args.output);
  std::string ext = lower_extension(output);
  if (ext != ".png" && ext != ".exr" && ext != ".tif" && ext != ".tiff")
    throw_input_error(args.output, "output must be .png, .tif (display-encoded) or .exr (linear)");
  fs::path out_dir = output.parent_path().empty() ? fs::path(".") : output.parent_path();
  if (!fs::is_directory(out_dir)) throw_input_error(args.output, "output folder does not exist");

  const EnhancementMethod& method = resolve_method(args.method);
  const bool enhanced = args.method.method != "none";
  if (ext == ".exr" && enhanced)
    throw_input_error(args.output, "enhanced stimuli are display-referred: write .png or .tif");

  Scene scene = load_scene(args.scene);
  if (args.refine) refine_scene(scene, *args.refine);
  if (args.width) scene.camera.width = *args.width;
  if (args.height) scene.camera.height = *args.height;
  if (args.spp) scene.settings.spp = *args.spp;
  if (args.seed) scene.settings.seed = uint64_t(*args.seed);
  if (args.exposure) scene.display.exposure_stops = *args.exposure;

  auto start = std::chrono::steady_clock::now();
  RayTracer tracer(scene);
  Progress progress("render");
  RenderOptions options;
  options.threads = args.threads.value_or(0);
  options.progress = [&](double f) { progress.update(f); };
  options.vertex_radiance = method.needs_vertex_radiance();
  options.ring_samples = args.ring_samples;
  RenderResult result = render(scene, tracer, options);
  RayCounts rays = result.rays;
  if (!args.aux.empty()) write_aux(args.aux, result.gbuffer);

  std::string details;
  if (ext == ".exr") {
    write_image(output, result.radiance);
  } else {
    View view = make_view(scene, std::move(result), args.bits);
    auto prepared = method.prepare(view, args.method.options);
    Composed stimulus = prepared->compose(args.method.lambda);
    write_image(output, stimulus.display, {args.bits});
    if (!args.aux.empty()) write_auxiliary(args.aux, *prepared);
    if (enhanced)
      details = ", " + args.method.method + " λ=" + format_number(args.method.lambda) + ", " +
                std::to_string(stimulus.clipped_pixels) + " clipped pixels, " + prepared->parameters().dump();
  }
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  char summary[256];
  std::snprintf(summary, sizeof summary, "wrote %s (%dx%d, %d spp, %s, %.2f M rays/s)", args.output.c_str(),
                scene.camera.width, scene.camera.height, scene.settings.spp, format_seconds(seconds).c_str(),
                double(rays.primary + rays.shadow) / seconds * 1e-6);
  progress.finish(summary + details);
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene description to an image.");
  cmd->add_option("scene", args->scene, "Scene description (JSON, see docs/scene-format.md)")->required();
  cmd->add_option("-o,--output", args->output,
                  "Output image: .png/.tif display-encoded, .exr linear radiance")->required();
  cmd->add_option("--method", args->method.method, "Enhancement method")
      ->check(CLI::IsMember(method_names()))
      ->capture_default_str();
  cmd->add_option("--sigma", args->method.options.sigma, "usm3d: smoothing width σ in world units");
  cmd->add_option("--sigma-fraction", args->method.options.sigma_fraction,
                  "usm3d: σ as a fraction of the scene's bounding-box diagonal");
  cmd->add_option("--iterations", args->method.options.iterations,
                  "usm3d: explicit number of smoothing iterations instead of σ");
  cmd->add_flag("--no-adapt", args->method.no_adapt, "usm3d: constant gain λ·w (no √(1+Var) adaptation)");
  add_image_method_options(cmd, args->method);
  cmd->add_option("--ring-samples", args->ring_samples,
                  "usm3d: anti-aliasing samples per incident triangle for the vertex signal (0 = off)")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  cmd->add_option("--refine", args->refine, "usm3d: split mesh edges longer than this world length first")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--width", args->width, "Override the camera's width in pixels")->check(CLI::Range(1, 16384));
  cmd->add_option("--height", args->height, "Override the camera's height in pixels")->check(CLI::Range(1, 16384));
  cmd->add_option("--spp", args->spp, "Samples per pixel (stratified)")->check(CLI::Range(1, 65536));
  cmd->add_option("--seed", args->seed, "Random seed; the same seed gives byte-identical output")
      ->check(CLI::Range(0ll, 1ll << 53));
  cmd->add_option("--exposure", args->exposure, "Override the exposure in stops")->check(CLI::Range(-30.0, 30.0));
  cmd->add_option("--bits", args->bits, "PNG/TIFF bit depth")->check(CLI::IsMember({8, 16}))->capture_default_str();
  cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 1024));
  cmd->add_option("--aux", args->aux,
                  "Also write depth.exr, normal.exr, object_id.exr and the method's intermediate images "
                  "(e.g. depth-usm's D, G*D and ΔD) to this folder");
  cmd->callback([args] { run(*args); });
  cmd->footer(
      "Examples:\n"
      "  countershade render experiments/scenes/clutter.json -o clutter.png\n"
      "  countershade render experiments/scenes/cornsweet-cube.json -o cube.png --method usm3d --lambda 1.5 "
      "--sigma-fraction 0.05\n"
      "  countershade render experiments/scenes/clutter.json -o dark.png --method depth-usm --operator darken "
      "--lambda 0.8 --kernel 5%");
}

}  // namespace countershade::cli
