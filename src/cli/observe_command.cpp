// `countershade observe`: how far a test image lies above its reference for the image-computable
// observer, in JND (docs/observer.md).

#include <algorithm>
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/observer_viewing.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/false_colour.h"
#include "core/image.h"
#include "observer/detection_model.h"
#include "observer/luminance_image.h"

namespace countershade::cli {
namespace {

struct ObserveArgs {
  std::string reference, test, map;
  ObserverViewingArgs viewing;
};

// The share of each pixel: false colour scaled to the largest share in PNG and TIFF, the shares
// themselves in float formats.
void write_share_map(const std::string& file, const observer::ContrastImage& share) {
  Image values(share.width, share.height, 1);
  const double top = *std::max_element(share.values.begin(), share.values.end());
  const std::string ext = lower_extension(file);
  const bool scaled = ext == ".png" || ext == ".tif" || ext == ".tiff";
  for (size_t i = 0; i < share.values.size(); ++i)
    values.pixels[i] = float(scaled ? (top > 0 ? share.values[i] / top : 0.0) : share.values[i]);
  write_image(file, scaled ? false_colour_image(values) : values);
}

void run(const ObserveArgs& args) {
  if (!args.map.empty())
    check_output_file(args.map, {".png", ".tif", ".tiff", ".exr", ".pfm"},
                      ".png, .tif, .exr or .pfm");
  const ObserverViewing viewing = observer_viewing(args.viewing, "observe");
  const auto reference = observer::read_luminance(args.reference, viewing.display);
  const auto test = observer::read_luminance(args.test, viewing.display);
  const auto contrast = observer::contrast_between(reference, test, args.reference, args.test);
  const observer::Observation seen =
      observer::observe(contrast, viewing.ppd, observer::kModelfestModel);
  if (!args.map.empty()) write_share_map(args.map, seen.share);
  std::printf("observe: %s against %s at %.4g pixels per degree%s\njnd %.4f\n", args.test.c_str(),
              args.reference.c_str(), viewing.ppd,
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
  add_observer_viewing_flags(cmd, args->viewing);
  cmd->add_option("--map", args->map,
                  "Write each pixel's share of the pooled response (PNG/TIFF: false colour "
                  "scaled to the largest share; EXR/PFM: the shares)");
  cmd->callback([args] { run(*args); });
  cmd->footer(
      "Examples:\n"
      "  countershade observe reference.png enhanced.png --ppd 36 --map where.png\n"
      "  countershade observe reference.png enhanced.png --display lab-display-at-57cm.json\n"
      "The response is the last line: jnd VALUE (docs/observer.md).");
}

}  // namespace countershade::cli
