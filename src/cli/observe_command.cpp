// `countershade observe`: how far a test image lies above its reference for the image-computable
// observer, in JND (docs/observer.md).

#include <algorithm>
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/display_calibration_file.h"
#include "core/error.h"
#include "core/false_colour.h"
#include "core/image.h"
#include "core/json_reader.h"
#include "observer/detection_model.h"
#include "observer/luminance_image.h"
#include "stimuli/screen.h"

namespace countershade::cli {
namespace {

struct ObserveArgs {
  std::string reference, test, map, display;
  double ppd = 0, peak_luminance = 100;
  bool peak_given = false;
};

// What the viewing condition gives: pixels per degree and the display's luminance.
struct Viewing {
  double ppd = 0;
  CalibratedDisplay display;
};

// --ppd and --peak-luminance, or a display file (docs/observer.md): its "screen" (as an
// experiment's, docs/display.md) gives the pixels per degree and its "calibration" (a file of
// `countershade calibrate`, relative to it) the luminance of each code.
Viewing viewing_of(const ObserveArgs& args) {
  Viewing v{args.ppd, observer::srgb_display(args.peak_luminance)};
  if (args.display.empty()) {
    if (args.ppd <= 0) throw InputError("observe: give --ppd or --display");
    return v;
  }
  const nlohmann::json j = parse_json_file(args.display);
  const JsonObject o(j, args.display, "");
  if (o.has("screen")) {
    if (args.ppd > 0) o.fail("screen", "gives the pixels per degree; leave out --ppd");
    v.ppd = read_screen(o.object("screen")).pixels_per_degree();
  } else if (args.ppd <= 0) {
    o.fail("screen", "is missing, and no --ppd was given");
  }
  if (o.has("calibration")) {
    if (args.peak_given) o.fail("calibration", "gives the luminance; leave out --peak-luminance");
    std::filesystem::path file = o.string("calibration");
    if (file.is_relative()) file = std::filesystem::path(args.display).parent_path() / file;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
      o.fail("calibration", "no such file '" + file.string() + "'");
    v.display = read_calibration_file(file);
  }
  o.finish();
  return v;
}

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
  const Viewing viewing = viewing_of(args);
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
  cmd->add_option("--ppd", args->ppd, "Pixels per degree of visual angle at the viewing distance")
      ->check(within(1, 10000));
  auto* peak = cmd->add_option("--peak-luminance", args->peak_luminance,
                               "cd/m² of full-scale white of an sRGB display, for images of codes")
                   ->check(within(0.01, 100000))
                   ->capture_default_str();
  cmd->add_option("--display", args->display,
                  "Display file: {\"screen\": {width_mm, width_px, distance_mm}, \"calibration\": "
                  "FILE of countershade calibrate}; either key may be left out");
  cmd->add_option("--map", args->map,
                  "Write each pixel's share of the pooled response (PNG/TIFF: false colour "
                  "scaled to the largest share; EXR/PFM: the shares)");
  cmd->callback([args, peak] {
    args->peak_given = peak->count() > 0;
    run(*args);
  });
  cmd->footer(
      "Examples:\n"
      "  countershade observe reference.png enhanced.png --ppd 36 --map where.png\n"
      "  countershade observe reference.png enhanced.png --display lab-display-at-57cm.json\n"
      "The response is the last line: jnd VALUE (docs/observer.md).");
}

}  // namespace countershade::cli
