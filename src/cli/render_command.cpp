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
#include "render/ray_tracer.h"
#include "render/renderer.h"
#include "render/scene.h"

namespace countershade::cli {
namespace {

namespace fs = std::filesystem;

struct RenderArgs {
  std::string scene;
  std::string output;
  std::string method = "none";
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

void run(const RenderArgs& args) {
  fs::path output(args.output);
  std::string ext = output.extension().string();
  for (auto& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
  if (ext != ".png" && ext != ".exr" && ext != ".tif" && ext != ".tiff")
    throw_input_error(args.output, "output must be .png, .tif (display-encoded) or .exr (linear)");
  fs::path out_dir = output.parent_path().empty() ? fs::path(".") : output.parent_path();
  if (!fs::is_directory(out_dir)) throw_input_error(args.output, "output folder does not exist");

  Scene scene = load_scene(args.scene);
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
  RenderResult result = render(scene, tracer, options);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (ext == ".exr")
    write_image(output, result.radiance);
  else
    write_image(output, encode_for_display(result.radiance, scene.display), {args.bits});
  if (!args.aux.empty()) write_aux(args.aux, result.gbuffer);

  char summary[256];
  std::snprintf(summary, sizeof summary, "wrote %s (%dx%d, %d spp, %s, %.2f M rays/s)",
                args.output.c_str(), scene.camera.width, scene.camera.height, scene.settings.spp,
                format_seconds(seconds).c_str(),
                double(result.rays.primary + result.rays.shadow) / seconds * 1e-6);
  progress.finish(summary);
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene description to an image.");
  cmd->add_option("scene", args->scene, "Scene description (JSON, see docs/scene-format.md)")->required();
  cmd->add_option("-o,--output", args->output,
                  "Output image: .png/.tif display-encoded, .exr linear radiance")->required();
  cmd->add_option("--method", args->method, "Enhancement method")
      ->check(CLI::IsMember({"none"}))
      ->capture_default_str();
  cmd->add_option("--width", args->width, "Override the camera's width in pixels")->check(CLI::Range(1, 16384));
  cmd->add_option("--height", args->height, "Override the camera's height in pixels")->check(CLI::Range(1, 16384));
  cmd->add_option("--spp", args->spp, "Samples per pixel (stratified)")->check(CLI::Range(1, 65536));
  cmd->add_option("--seed", args->seed, "Random seed; the same seed gives byte-identical output")
      ->check(CLI::Range(0ll, 1ll << 53));
  cmd->add_option("--exposure", args->exposure, "Override the exposure in stops")->check(CLI::Range(-30.0, 30.0));
  cmd->add_option("--bits", args->bits, "PNG/TIFF bit depth")->check(CLI::IsMember({8, 16}))->capture_default_str();
  cmd->add_option("--threads", args->threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 1024));
  cmd->add_option("--aux", args->aux, "Also write depth.exr, normal.exr and object_id.exr to this folder");
  cmd->callback([args] { run(*args); });
}

}  // namespace countershade::cli
