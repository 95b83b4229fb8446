// `countershade congruence`: the congruence between an image's shading flow and its shape flow
// (docs/enhancement-methods.md, "Congruence score").

#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/image_inputs.h"
#include "core/atomic_file.h"
#include "core/display.h"
#include "core/false_colour.h"
#include "stimuli/congruence.h"

namespace countershade::cli {
namespace {

struct CongruenceArgs {
  std::string image, depth, map;
};

void run(const CongruenceArgs& args) {
  if (!args.map.empty()) check_output_file(args.map, {".png", ".tif", ".tiff", ".exr"}, ".png, .tif or .exr");
  int bits = 0;
  const Image display = load_display_image(args.image, bits);
  const std::vector<float> depth = load_depth(args.depth, "depth", display.width, display.height);
  const Congruence c = display_congruence(display, DisplayEncoding{}, bits, depth);
  if (!args.map.empty()) write_image(args.map, false_colour_image(c.map));
  std::printf("congruence: %s, %zu interior pixels%s, score %.6f\n", args.image.c_str(), c.interior_pixels,
              args.map.empty() ? "" : (", map " + args.map).c_str(), c.score);
}

}  // namespace

void add_congruence_command(CLI::App& app) {
  auto args = std::make_shared<CongruenceArgs>();
  CLI::App* cmd = app.add_subcommand(
      "congruence", "Score how well an image's shading flow follows its shape (depth) flow, from 0 to 1.");
  cmd->add_option("image", args->image, "Image: PNG/TIFF/JPEG as sRGB code values, EXR/HDR/PFM as linear")->required();
  cmd->add_option("--depth", args->depth, "Depth map of the same size (EXR, PFM, PNG-16, TIFF); 0, inf and NaN are background")
      ->required();
  cmd->add_option("--map", args->map, "Write the per-pixel score in false colour (viridis: 0 dark blue, 1 yellow)");
  cmd->callback([args] { run(*args); });
  cmd->footer(
      "Examples:\n"
      "  countershade render scene.json -o image.png --aux aux\n"
      "  countershade congruence image.png --depth aux/depth.exr --map congruence.png\n"
      "The score is the last number of the summary line.");
}

}  // namespace countershade::cli
