#include "cli/observer_viewing.h"

#include <filesystem>

#include "cli/commands.h"
#include "core/error.h"
#include "core/json_reader.h"
#include "core/progress.h"
#include "observer/luminance_image.h"
#include "stimuli/screen.h"

namespace countershade::cli {

void add_observer_viewing_flags(CLI::App* cmd, ObserverViewingArgs& args) {
  cmd->add_option("--ppd", args.ppd, "Pixels per degree of visual angle at the viewing distance")
      ->check(within(1, 10000));
  args.peak_option =
      cmd->add_option("--peak-luminance", args.peak_luminance,
                      "cd/m² of full-scale white of an sRGB display, for images of codes")
          ->check(within(0.01, 100000))
          ->capture_default_str();
  cmd->add_option("--display", args.display,
                  "Display file: {\"screen\": {width_mm, width_px, distance_mm}, \"calibration\": "
                  "FILE of countershade calibrate}; either key may be left out");
}

namespace {

CalibratedDisplay calibration_named(const JsonObject& o, const std::string& display_file) {
  std::filesystem::path file = o.string("calibration");
  if (file.is_relative()) file = std::filesystem::path(display_file).parent_path() / file;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    o.fail("calibration", "no such file '" + file.string() + "'");
  return read_calibration_file(file);
}

}  // namespace

ObserverViewing observer_viewing(const ObserverViewingArgs& args, const std::string& command,
                                 std::optional<double> fallback_ppd) {
  const bool peak_given = args.peak_option && args.peak_option->count() > 0;
  ObserverViewing v{args.ppd, observer::srgb_display(args.peak_luminance)};
  const bool ppd_given = args.ppd > 0;
  if (!ppd_given && fallback_ppd) v.ppd = *fallback_ppd;
  if (args.display.empty()) {
    if (v.ppd <= 0) throw InputError(command + ": give --ppd or --display");
    return v;
  }
  const nlohmann::json j = parse_json_file(args.display);
  const JsonObject o(j, args.display, "");
  if (o.has("screen")) {
    if (ppd_given) o.fail("screen", "gives the pixels per degree; leave out --ppd");
    v.ppd = read_screen(o.object("screen")).pixels_per_degree();
  } else if (v.ppd <= 0) {
    o.fail("screen", "is missing, and no --ppd was given");
  }
  if (o.has("calibration")) {
    if (peak_given) o.fail("calibration", "gives the luminance; leave out --peak-luminance");
    v.display = calibration_named(o, args.display);
  }
  o.finish();
  return v;
}

observer::SetPrediction predict_with_progress(const Manifest& manifest,
                                              const std::filesystem::path& manifest_path,
                                              const ObserverViewing& viewing, int jobs,
                                              const std::string& label) {
  observer::PredictionSettings settings;
  settings.ppd = viewing.ppd;
  settings.display = viewing.display;
  settings.threads = jobs;
  Progress progress(label);
  settings.progress = [&progress](double f) { progress.update(f); };
  auto prediction = observer::predict_set(manifest, manifest_path.parent_path(), settings);
  progress.finish(std::to_string(prediction.conditions.size()) + " conditions");
  return prediction;
}

}  // namespace countershade::cli
