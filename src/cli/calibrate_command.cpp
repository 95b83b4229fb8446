// `countershade calibrate`: photometer readings → the display block (a lookup table) and the gamma
// fits of every gun (analysis/display_calibration.h; docs/display.md).

#include <cstdio>
#include <filesystem>
#include <memory>

#include "analysis/display_calibration.h"
#include "cli/commands.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/svg_plot.h"

namespace countershade::cli {
namespace {

namespace fs = std::filesystem;
using analysis::GammaFit;

struct CalibrateArgs {
  std::string readings, output;
  int bits = 8;
};

const GammaFit& psyphy_fit(const std::vector<GammaFit>& fits) { return fits.front(); }

// The readings of one gun against each model's curve.
void write_figure(const fs::path& path, const std::string& gun,
                  const std::vector<analysis::Reading>& readings,
                  const std::vector<GammaFit>& fits) {
  LinePlot plot;
  plot.title = "gun " + gun + ": readings and fits";
  plot.x_label = "level (0 to 1)";
  plot.y_label = "luminance (cd/m²)";
  PlotSeries measured{"readings", {}, {}, "#000000"};
  measured.points = true;
  for (const auto& r : readings) measured.x.push_back(r.level), measured.y.push_back(r.luminance);
  plot.series.push_back(measured);
  for (size_t m = 0; m < fits.size(); ++m) {
    PlotSeries curve{fits[m].model, {}, {}, plot_color(m)};
    for (int i = 0; i <= 100; ++i)
      curve.x.push_back(i / 100.0), curve.y.push_back(fits[m].predict(i / 100.0));
    plot.series.push_back(curve);
  }
  plot.write(path);
}

void run(const CalibrateArgs& args) {
  const fs::path out = args.output, base = out.parent_path() / out.stem();
  check_output_file(args.output, {".json"}, "a JSON file (DISPLAY.json)");
  const analysis::GunReadings guns = analysis::read_photometer_readings(args.readings, args.bits);
  std::map<std::string, std::vector<GammaFit>> fits;
  for (const auto& [gun, readings] : guns) fits[gun] = analysis::fit_gamma_models(readings);
  // The table follows the grey (W) readings where there are any, else the sum of the guns.
  std::vector<const GammaFit*> table_from;
  for (const auto& [gun, models] : fits)
    if (gun == "W" || !fits.count("W")) table_from.push_back(&psyphy_fit(models));
  const std::string lut = analysis::lookup_table_csv(table_from, args.bits);
  double black = 0, white = 0;
  for (const GammaFit* f : table_from) black += f->predict(0), white += f->predict(1);
  nlohmann::ordered_json display = {
      {"readings", fs::path(args.readings).filename().string()},
      {"bits", args.bits},
      {"display", {{"encoding", "lut"}, {"lut", base.filename().string() + ".lut.csv"}}},
      {"luminance_cd_m2", {{"black", black}, {"white", white}}},
      {"lookup_table_from", fits.count("W") ? "W, psyphy fit" : "R + G + B, psyphy fits"},
      {"fits", analysis::fits_to_json(fits)}};
  write_text_atomically(base.string() + ".lut.csv", lut);
  for (const auto& [gun, readings] : guns)
    write_figure(base.string() + "-" + gun + ".svg", gun, readings, fits.at(gun));
  write_text_atomically(out, display.dump(2) + "\n");
  std::fprintf(stderr,
               "calibrate: wrote %s (%zu guns; black %.4g cd/m², white %.4g cd/m²), its lookup "
               "table and figures\n",
               args.output.c_str(), guns.size(), black, white);
}

}  // namespace

void add_calibrate_command(CLI::App& app) {
  auto args = std::make_shared<CalibrateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "calibrate",
      "Fit a display's gamma from photometer readings; write its lookup table and the fits.");
  cmd->add_option("readings", args->readings,
                  "CSV of readings: gun (R, G, B or W), code_value (0 … 2^bits − 1) or gl (0 … 1), "
                  "lum_cd_m2")
      ->required();
  cmd->add_option(
         "-o,--output", args->output,
         "DISPLAY.json; also writes DISPLAY.lut.csv (the lookup table) and DISPLAY-<gun>.svg")
      ->required();
  cmd->add_option("--bits", args->bits,
                  "The display's bits per channel: the range of code_value and the table's rows")
      ->check(CLI::Range(1, 16))
      ->capture_default_str();
  cmd->callback([args] { run(*args); });
  cmd->footer(
      "\nExample:\n  countershade calibrate readings.csv -o lab-display.json\n"
      "The scene's display block then names it: \"display\": {\"calibration\": "
      "\"lab-display.json\"} "
      "(docs/display.md).");
}

}  // namespace countershade::cli
