// `countershade render`: one scene to one image, plus optional auxiliary buffers.

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

// The output's format, checked before any work.
std::string check_output(const RenderArgs& args, bool enhanced) {
  const std::string ext = check_output_file(args.output, {".png", ".tif", ".tiff", ".exr"},
                                            ".png, .tif (display-encoded) or .exr (linear)");
  if (ext == ".exr" && enhanced) throw_input_error(args.output, "enhanced stimuli are display-referred: write .png or .tif");
  return ext;
}

std::shared_ptr<Scene> load_render_scene(const RenderArgs& args, const RenderRequest& request) {
  auto scene = std::make_shared<Scene>(load_scene(args.scene));
  apply_request(*scene, request);
  if (args.width) scene->camera.width = *args.width;
  if (args.height) scene->camera.height = *args.height;
  if (args.spp) scene->settings.spp = *args.spp;
  if (args.seed) scene->settings.seed = uint64_t(*args.seed);
  if (args.exposure) scene->display.exposure_stops = *args.exposure;
  return scene;
}

void run(const RenderArgs& args, const CLI::App* cmd) {
  const ResolvedMethod method = resolve_method(cmd, args.method);
  const bool enhanced = method.method->enhances();
  const std::string ext = check_output(args, enhanced);
  std::shared_ptr<const Scene> scene = load_render_scene(args, method.request);

  auto start = std::chrono::steady_clock::now();
  Progress progress("render");
  ViewOptions vo;
  vo.bits = args.bits;
  vo.threads = args.threads.value_or(0);
  vo.progress = [&](double f) { progress.update(f); };
  std::shared_ptr<const View> view = render_view(scene, method.request, vo);
  if (!args.aux.empty()) write_aux(args.aux, view->render.gbuffer);

  std::string details;
  if (ext == ".exr") {
    write_image(args.output, view->render.radiance);
  } else {
    auto prepared = method.method->prepare(make_context(view, vo.threads), *method.parameters);
    Composed stimulus = prepared->compose(args.method.lambda);
    write_image(args.output, stimulus.display, {args.bits});
    if (!args.aux.empty()) write_auxiliary(args.aux, *prepared);
    if (enhanced)
      details = ", " + method.method->name() + " λ=" + format_number(args.method.lambda) + ", " +
                std::to_string(stimulus.clipped_pixels) + " clipped pixels, " + prepared->parameters().dump();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const RayCounts& rays = view->render.rays;
  char summary[256];
  std::snprintf(summary, sizeof summary, "wrote %s (%dx%d, %d spp, %s, %.2f M rays/s)", args.output.c_str(),
                scene->camera.width, scene->camera.height, scene->settings.spp, format_seconds(seconds).c_str(),
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
  add_method_options(cmd, args->method, "Enhancement method (`countershade methods` lists them)");
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
  cmd->callback([args, cmd] { run(*args, cmd); });
  cmd->footer(method_parameters_help() +
              "\nExamples:\n"
              "  countershade render experiments/scenes/clutter.json -o clutter.png\n"
              "  countershade render experiments/scenes/cornsweet-cube.json -o cube.png --method usm3d --lambda 1.5 "
              "--sigma-fraction 0.05\n"
              "  countershade render experiments/scenes/clutter.json -o dark.png --method depth-usm --operator darken "
              "--lambda 0.8 --kernel 5%");
}

}  // namespace countershade::cli
