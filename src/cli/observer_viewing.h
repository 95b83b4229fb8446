#pragma once
// The viewing condition of the image-computable observer's commands (observe, predict): pixels per
// degree and the luminance of each display code, from flags or from a display file
// (docs/observer.md).

#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "core/display_calibration_file.h"
#include "formats/manifest.h"
#include "observer/set_prediction.h"

namespace countershade::cli {

struct ObserverViewingArgs {
  std::string display;
  double ppd = 0, peak_luminance = 100;
  CLI::Option* peak_option = nullptr;  // to tell a given --peak-luminance from its default
};

struct ObserverViewing {
  double ppd = 0;
  CalibratedDisplay display;
};

// --ppd, --peak-luminance and --display.
void add_observer_viewing_flags(CLI::App* cmd, ObserverViewingArgs& args);

// --ppd and --peak-luminance, or a display file: its "screen" (as an experiment's,
// docs/display.md) gives the pixels per degree and its "calibration" (a file of `countershade
// calibrate`, relative to it) the luminance of each code. `fallback_ppd` serves when neither gives
// pixels per degree (a set's recorded screen). Throws InputError naming `command` or the file.
ObserverViewing observer_viewing(const ObserverViewingArgs& args, const std::string& command,
                                 std::optional<double> fallback_ppd = std::nullopt);

// The set's prediction at `viewing` on `jobs` threads, with a progress bar labelled `label`.
observer::SetPrediction predict_with_progress(const Manifest& manifest,
                                              const std::filesystem::path& manifest_path,
                                              const ObserverViewing& viewing, int jobs,
                                              const std::string& label);

}  // namespace countershade::cli
