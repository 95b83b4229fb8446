// `countershade predict`: where the image-computable observer expects each condition of a stimulus
// set to become visible, preferred and too strong (docs/observer.md).

#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/observer_viewing.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/number_format.h"
#include "formats/manifest.h"
#include "observer/prediction_report.h"

namespace countershade::cli {
namespace {

struct PredictArgs {
  std::string manifest, out;
  ObserverViewingArgs viewing;
  int jobs = 0;
};

std::string display_in_words(const ObserverViewingArgs& args, const CalibratedDisplay& display) {
  if (args.display.empty() || display.white_cd_m2 == 0)
    return "an sRGB display, white at " + observer::rounded(args.peak_luminance) + " cd/m²";
  return "the display of " + args.display + ", " + observer::rounded(display.black_cd_m2) + " to " +
         observer::rounded(display.white_cd_m2) + " cd/m²";
}

void print_summary(const observer::SetPrediction& prediction) {
  for (const auto& c : prediction.conditions) {
    std::printf("  %s %s σ %s: λ", c.scene.c_str(), c.method.c_str(),
                format_value(c.sigma).c_str());
    for (size_t l = 0; l < c.lambda_at.size(); ++l)
      std::printf(l == 0 ? " %s at %g JND" : ", %s at %g JND",
                  c.lambda_at[l] ? observer::rounded(*c.lambda_at[l]).c_str() : "beyond the grid",
                  observer::kPredictionLevels[l]);
    std::printf("\n");
  }
}

void run(const PredictArgs& args) {
  const Manifest manifest = read_verified_manifest(args.manifest);
  check_output_folder(args.out);
  const ObserverViewing viewing =
      observer_viewing(args.viewing, "predict", manifest.viewing.pixels_per_degree);
  const observer::SetPrediction prediction =
      predict_with_progress(manifest, args.manifest, viewing, args.jobs, "predict");
  const observer::PredictionContext context{manifest.experiment_name, args.manifest,
                                            display_in_words(args.viewing, viewing.display),
                                            viewing.ppd, observer::kModelfestModel};
  observer::write_prediction(args.out, prediction, context);
  print_summary(prediction);
  if (prediction.sequence_conditions_skipped > 0)
    std::printf("predict: left out %zu sequence condition(s): the model is static\n",
                prediction.sequence_conditions_skipped);
  std::printf("predict: wrote %s/predicted_thresholds.csv, predicted_jnd.csv and report.html\n",
              args.out.c_str());
}

}  // namespace

void add_predict_command(CLI::App& app) {
  auto args = std::make_shared<PredictArgs>();
  CLI::App* cmd = app.add_subcommand(
      "predict",
      "Predict each condition's JND against λ, and the λ at 1, 2 and 4 JND, from a set's images.");
  cmd->add_option("manifest", args->manifest, "manifest.json of a stimulus set")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("-o,--output", args->out,
                  "Folder for predicted_thresholds.csv, "
                  "predicted_jnd.csv and report.html")
      ->required();
  add_observer_viewing_flags(cmd, args->viewing);
  cmd->add_option("--jobs", args->jobs, "Threads (default: all cores)")->check(CLI::Range(1, 1024));
  cmd->callback([args] { run(*args); });
  cmd->footer(
      "The pixels per degree come from --ppd, the display file's screen or the set's own screen.\n"
      "Examples:\n"
      "  countershade predict stimuli/cornsweet/manifest.json -o predicted/cornsweet --ppd 40\n"
      "  countershade predict stimuli/ritschel2008/manifest.json -o predicted/ritschel2008 \\\n"
      "      --display lab-display-at-57cm.json");
}

}  // namespace countershade::cli
