// `countershade image-filter`: one of texture-filter's filters applied to an image file, e.g. to
// filter a texture beforehand (a scene that samples the result renders exactly like
// `--method texture-filter --mode texture` on the original).

#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/color.h"
#include "core/error.h"
#include "enhance/filtered_pyramid.h"

namespace countershade::cli {
namespace {

struct ImageFilterArgs {
  std::string input, output, encoding = "srgb", borders = "wrap";
  double lambda = 1.0;
};

// Display code values for 8/16-bit outputs, the linear values themselves for float outputs.
Image output_image(const TextureLevel& level, const std::string& extension) {
  Image image = image_from_level(level);
  if (extension == ".exr") return image;
  for (float& v : image.pixels) v = float(srgb_encode(v));
  return image;
}

void run(const CLI::App* cmd, const ImageFilterArgs& args) {
  const std::string extension =
      check_output_file(args.output, {".exr", ".png", ".tif", ".tiff"}, ".exr, .png or .tif");
  if (!std::isfinite(args.lambda)) throw InputError("--lambda: must be a finite number");
  const ParameterBag bag = ParameterBag::from_arguments(cmd->remaining());
  const LightnessFilter filter = read_lightness_filter(bag);
  bag.finish("image-filter");
  Image image = read_image(args.input);
  check_finite(args.input, image);
  const TextureLevel plain = level_from_image(image, args.encoding == "srgb");
  const Borders borders = args.borders == "wrap" ? Borders::wrap : Borders::clamp;
  const std::vector<float> detail =
      lightness_detail(level_lightness(plain), plain.width, plain.height, filter, borders);
  write_image(args.output, output_image(with_detail(plain, detail, args.lambda), extension));
  std::printf("image-filter: %s -> %s, %s, sigma %g, lambda %g\n", args.input.c_str(),
              args.output.c_str(), filter_name(filter.kind).c_str(), filter.sigma, args.lambda);
}

}  // namespace

void add_image_filter_command(CLI::App& app) {
  auto args = std::make_shared<ImageFilterArgs>();
  CLI::App* cmd = app.add_subcommand(
      "image-filter",
      "Filter an image (a texture) with texture-filter's unsharp, bilateral or dog filter.");
  cmd->add_option("input", args->input, "Image to filter (PNG, TIFF, JPEG, EXR, ...)")->required();
  cmd->add_option("output", args->output,
                  "Result: .exr keeps the linear values exactly; .png/.tif are sRGB-encoded")
      ->required();
  cmd->add_option("--lambda", args->lambda, "Strength λ of the filter")->capture_default_str();
  cmd->add_option("--encoding", args->encoding,
                  "How the input's values are encoded (as a scene's texture_encoding)")
      ->check(CLI::IsMember({"srgb", "linear"}))
      ->capture_default_str();
  cmd->add_option("--borders", args->borders, "wrap (a texture) or clamp (an image)")
      ->check(CLI::IsMember({"wrap", "clamp"}))
      ->capture_default_str();
  cmd->allow_extras();  // the filter's keys
  cmd->callback([cmd, args] { run(cmd, *args); });
  cmd->footer(
      "Filter keys: --filter unsharp|bilateral|dog (unsharp), --sigma S in texels (2),\n"
      "  bilateral: --sigma-r (10, in L*); dog: --tau (1, in L*), --phi (0.5, per L*).\n"
      "Example: filter spot's texture, then render a scene whose material reads the result with\n"
      "\"texture_encoding\": \"linear\":\n"
      "  countershade image-filter spot_texture.png spot_unsharp.exr --filter unsharp --sigma 2 "
      "--lambda 1");
}

}  // namespace countershade::cli
