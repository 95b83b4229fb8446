// `countershade congruence`: the congruence between an image's shading flow and its shape flow
// (docs/enhancement-methods.md, "Congruence score").

#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/image_inputs.h"
#include "core/atomic_file.h"
#include "core/display.h"
#include "core/false_colour.h"
#include "measures/congruence.h"

namespace countershade::cli {
namespace {

struct CongruenceArgs {
  std::string image, depth, map, penalty = "signed";
  double tensor_sigma = 2;
};

void run(const CongruenceArgs& args) {
  if (!args.map.empty())
    check_output_file(args.map, {".png", ".tif", ".tiff", ".exr"}, ".png, .tif or .exr");
  int bits = 0;
  const Image display = load_display_image(args.image, bits);
  const std::vector<float> depth = load_depth(args.depth, "depth", display.width, display.height);
  CongruenceOptions options;
  options.penalty =
      args.penalty == "absolute" ? CongruencePenalty::absolute : CongruencePenalty::signed_clamp;
  options.tensor_sigma = args.tensor_sigma;
  const Congruence c = display_congruence(display, DisplayEncoding{}, bits, depth, options);
  if (!args.map.empty()) write_image(args.map, false_colour_image(c.map));
  std::printf("congruence: %s, %zu interior pixels%s, score %.6f\n", args.image.c_str(),
              c.interior_pixels, args.map.empty() ? "" : (", map " + args.map).c_str(), c.score);
}

}  // namespace

void add_congruence_command(CLI::App& app) {
  auto args = std::make_shared<CongruenceArgs>();
  CLI::App* cmd = app.add_subcommand(
      "congruence",
      "Score how well an image's shading flow follows its shape (depth) flow, from 0 to 1.");
  cmd->add_option("image", args->image,
                  "Image: PNG/TIFF/JPEG as sRGB code values, EXR/HDR/PFM as linear")
      ->required();
  cmd->add_option(
         "--depth", args->depth,
         "Depth map of the same size (EXR, PFM, PNG-16, TIFF); 0, inf and NaN are background")
      ->required();
  cmd->add_option("--map", args->map,
                  "Write the per-pixel score in false colour (viridis: 0 dark blue, 1 yellow)");
  cmd->add_option("--penalty", args->penalty,
                  "signed: shading stronger than shape costs nothing (the paper's clamp); "
                  "absolute: |e_c − e_s| "
                  "is penalised both ways (the earlier reading, for old figures)")
      ->check(CLI::IsMember({"signed", "absolute"}))
      ->capture_default_str();
  cmd->add_option("--tensor-sigma", args->tensor_sigma,
                  "σ_t of the structure tensors' Gaussian, pixels (0.5 to 50)")
      ->check(CLI::Range(0.5, 50.0))
      ->capture_default_str();
  cmd->callback([args] { run(*args); });
  cmd->footer(
      "Examples:\n"
      "  countershade render scene.json -o image.png --aux aux\n"
      "  countershade congruence image.png --depth aux/depth.exr --map congruence.png\n"
      "The score is the last number of the summary line.");
}

}  // namespace countershade::cli
