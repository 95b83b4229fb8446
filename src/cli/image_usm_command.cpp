// `countershade image-usm`: 2D or depth-buffer unsharp masking of an external image (a
// photograph, a stereo data set, another renderer's output) with an optional depth or
// disparity map.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli/commands.h"
#include "cli/image_inputs.h"
#include "cli/method_options.h"
#include "core/atomic_file.h"
#include "core/color.h"
#include "core/error.h"
#include "core/image.h"

namespace countershade::cli {
namespace {

namespace fs = std::filesystem;

struct ImageUsmArgs {
  std::string image, depth, depth_kind = "depth", output, aux;
  MethodArgs method;
  std::optional<int> bits;
};

// What an external image cannot give: a scene. Checked before anything is read.
void check_image_method(const ResolvedMethod& method, const ImageUsmArgs& args) {
  const std::string& name = method.method->name();
  if (method.request.scene || method.request.vertex_radiance)
    throw InputError("--method: " + name +
                     " works on a rendered scene's surfaces; use `countershade render`");
  if (method.request.depth && args.depth.empty())
    throw InputError("--depth: " + name + " needs a depth or disparity map");
}

void run(const ImageUsmArgs& args, const CLI::App* cmd) {
  const ResolvedMethod method = resolve_method(cmd, args.method);
  check_image_method(method, args);
  check_output_file(args.output, {".png", ".tif", ".tiff", ".exr"}, ".png, .tif or .exr");
  if (!args.aux.empty()) check_output_folder(args.aux);  // before anything is written

  int file_bits = 8;
  Image display = load_display_image(args.image, file_bits);
  const int bits = args.bits.value_or(file_bits == 16 ? 16 : 8);
  std::vector<float> depth;
  if (!args.depth.empty())
    depth = load_depth(args.depth, args.depth_kind, display.width, display.height);
  auto view = make_image_view(std::move(display), std::move(depth), DisplayEncoding::srgb(), bits);

  auto prepared = method.method->prepare(make_context(view), *method.parameters);
  Composed result = prepared->compose(args.method.lambda);
  if (lower_extension(args.output) ==
      ".exr") {  // back to linear values, like the input EXR convention
    for (float& v : result.display.pixels) v = float(srgb_decode(v));
    write_image(args.output, result.display);
  } else {
    write_image(args.output, result.display, {bits});
  }
  if (!args.aux.empty()) write_auxiliary(args.aux, *prepared);
  std::fprintf(stderr, "image-usm: wrote %s (%dx%d, %s λ=%g, %zu clipped pixels, %s)\n",
               args.output.c_str(), view->width(), view->height(), method.method->name().c_str(),
               args.method.lambda, result.clipped_pixels, prepared->parameters().dump().c_str());
}

}  // namespace

void add_image_usm_command(CLI::App& app) {
  auto args = std::make_shared<ImageUsmArgs>();
  CLI::App* cmd = app.add_subcommand(
      "image-usm",
      "2D or depth-buffer unsharp masking of an external image with an optional depth map.");
  cmd->add_option("image", args->image,
                  "Image: PNG (8/16-bit), TIFF or JPEG as sRGB code values; EXR/HDR/PFM as linear")
      ->required();
  cmd->add_option("--depth", args->depth,
                  "Depth or disparity map of the same size (PNG-16, EXR, PFM, TIFF)");
  cmd->add_option("--depth-kind", args->depth_kind,
                  "What the map holds: depth, or disparity (depth ∝ 1/disparity)")
      ->check(CLI::IsMember({"depth", "disparity"}))
      ->capture_default_str();
  cmd->add_option("-o,--output", args->output, "Output image (.png, .tif or .exr)")->required();
  add_method_options(cmd, args->method,
                     "An image-space method, e.g. usm2d or depth-usm (`countershade methods`)");
  cmd->get_option("--method")->required();
  cmd->add_option("--bits", args->bits, "PNG/TIFF bit depth (default: the input's)")
      ->check(CLI::IsMember({8, 16}));
  cmd->add_option("--aux", args->aux,
                  "Write the method's intermediate images (e.g. D, G*D, ΔD) as EXR here");
  cmd->callback([args, cmd] { run(*args, cmd); });
  cmd->footer(method_parameters_help() +
              "\nExamples:\n"
              "  countershade image-usm photo.png --depth depth.exr -o out.png --method depth-usm "
              "--operator darken "
              "--lambda 0.8 --kernel 5%\n"
              "  countershade image-usm im0.png --depth disp0.pfm --depth-kind disparity -o "
              "out.png --method depth-usm "
              "--operator color --lambda 2 --kernel 3%\n"
              "  countershade image-usm photo.png -o sharp.png --method usm2d --lambda 1 "
              "--sigma-percent 1");
}

}  // namespace countershade::cli
