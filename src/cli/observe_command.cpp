// `countershade observe`: how far a test image lies above its reference for the image-computable
// observer, in JND (docs/observer.md).

#include <algorithm>
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/false_colour.h"
#include "core/image.h"
#include "observer/detection_model.h"
#include "observer/luminance_image.h"

namespace countershade::cli {
namespace {

struct ObserveArgs {
  std::string reference, test, map;
  double ppd = 0, peak_luminance = 100;
};

// The share of each pixel: false colour scaled to the largest share in PNG and TIFF, the shares
// themselves in float formats.
void write_share_map(const std::string& file, const observer::ContrastImage& share) {
  Image values(share.width, share.height, 1);
  const double top = *std::max_element(share.values.begin(), share.values.end());
  const bool scaled = lower_extension(file) == ".png" || lower_extension(file) == ".tif" ||
                      lower_extension(file) == ".tiff";
  for (size_t i = 0; i < share.values.size(); ++i)
    values.pixels[i] = float(scaled ? (top > 0 ? share.values[i] / top : 0.0) : share.values[i]);
  write_image(file, scaled ? false_colour_image(values) : values);
}

void run(const ObserveArgs& args) {
  if (!args.map.empty())
    check_output_file(args.map, {".png", ".tif", ".tiff", ".exr", ".pfm"},
                      ".png, .tif, .exr or .pfm");
  const auto reference = observer::read_luminance(args.reference, args.peak_luminance);
  const auto test = observer::read_luminance(args.test, args.peak_luminance);
  const auto contrast = observer::contrast_between(reference, test, args.reference, args.test);
  const observer::Observation seen =
      observer::observe(contrast, args.ppd, observer::kModelfestModel);
  if (!args.map.empty()) write_share_map(args.map, seen.share);
  std::printf("observe: %s against %s at %g pixels per degree%s\njnd %.4f\n", args.test.c_str(),
              args.reference.c_str(), args.ppd,
              args.map.empty() ? "" : (", map " + args.map).c_str(), seen.jnd);
}

}  // namespace

void add_observe_command(CLI::App& app) {
  auto args = std::make_shared<ObserveArgs>();
  CLI::App* cmd = app.add_subcommand(
      "observe",
      "How visible a test image's difference from its reference is, in JND (1: threshold).");
  cmd->add_option("reference", args->reference,
                  "Reference image: PNG/TIFF/JPEG as sRGB codes, PFM/EXR/HDR as cd/m²")
      ->required();
  cmd->add_option("test", args->test, "Test image of the same size and kind")->required();
  cmd->add_option("--ppd", args->ppd, "Pixels per degree of visual angle at the viewing distance")
      ->check(within(1, 10000))
      ->required();
  cmd->add_option("--peak-luminance", args->peak_luminance,
                  "cd/m² of full-scale white, for images of display codes")
      ->check(within(0.01, 100000))
      ->capture_default_str();
  cmd->add_option("--map", args->map,
                  "Write each pixel's share of the pooled response (PNG/TIFF: false colour "
                  "scaled to the largest share; EXR/PFM: the shares)");
  cmd->callback([args] { run(*args); });
  cmd->footer(
      "Examples:\n"
      "  countershade observe reference.png enhanced.png --ppd 36 --map where.png\n"
      "The response is the last line: jnd VALUE (docs/observer.md).");
}

}  // namespace countershade::cli
