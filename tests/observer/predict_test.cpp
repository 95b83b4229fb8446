// `countershade predict` on a small real set: every image's JND is what `observe` says of it, each
// level's λ is where a luminance mix of its two grid neighbours reaches the level (checked by
// `observe` on that mix, written as luminance), the control condition reaches no level, and bad
// input is one line and exit 2.

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "core/image.h"
#include "core/number_format.h"
#include "formats/responses.h"
#include "observer/luminance_image.h"
#include "observer/set_prediction.h"
#include "test_util.h"

namespace countershade::observer {
namespace {

namespace fs = std::filesystem;

constexpr double kPredictPpd = 20;

// An image of two bumps: `a` on the left, `b` on the right, as filtered responses would be.
ContrastImage two_bumps(double a, double b) {
  ContrastImage image(32, 16);
  for (int y = 4; y < 12; ++y)
    for (int x = 4; x < 12; ++x) {
      image.at(x, y) = a;
      image.at(x + 16, y) = b;
    }
  return image;
}

TEST(LambdaReaching, FindsTheLevelOnTheMixOfTwoResponses) {
  const DetectionModel model{1.0, 2.5, false};
  // From nothing, the response grows linearly: the level's share of the way.
  const ContrastImage nothing(32, 16), bump = two_bumps(0.3, 0.0);
  const double full = filtered_response_jnd(bump, kPredictPpd, model);
  EXPECT_NEAR(lambda_reaching(0.25 * full, nothing, 1.0, bump, 2.0, kPredictPpd, model), 1.25,
              1e-6);
  // Between two different patterns the response is not linear in the mix; the λ found gives the
  // level when the mix is evaluated directly.
  const ContrastImage a = two_bumps(0.2, 0.0), b = two_bumps(0.0, 0.5);
  const double level = 0.5 * (filtered_response_jnd(a, kPredictPpd, model) +
                              filtered_response_jnd(b, kPredictPpd, model));
  const double lambda = lambda_reaching(level, a, 0.0, b, 0.5, kPredictPpd, model);
  const double t = lambda / 0.5;
  ContrastImage mix = a;
  for (size_t k = 0; k < mix.values.size(); ++k)
    mix.values[k] = (1 - t) * a.values[k] + t * b.values[k];
  EXPECT_NEAR(filtered_response_jnd(mix, kPredictPpd, model), level, 1e-5 * level);
  EXPECT_GT(std::abs(t - 0.5), 0.01) << "the test needs a mix that is not linear";
}

double jnd_of(const std::string& output) {
  const auto at = output.rfind("jnd ");
  return at == std::string::npos ? NAN : std::stod(output.substr(at + 4));
}

// A Cornsweet edge on a grey field (responds) and 3D unsharp masking of the same field (the
// control: nothing to enhance).
fs::path small_set(const fs::path& dir) {
  const fs::path scene = testing::source_dir() / "experiments/cornsweet/scenes/grey.json";
  const fs::path experiment =
      testing::write_file(dir / "experiment.json", R"({
    "version": 1, "name": "edges", "seed": 1,
    "lambda": {"min": 0, "max": 1, "step": 0.25},
    "scenes": [{"name": "grey", "file": ")" + scene.string() +
                                                       R"(", "width": 64, "height": 48, "spp": 4}],
    "methods": [{"method": "cornsweet", "mode": "image", "sigma_px": [3], "amplitude": 1},
                {"method": "usm3d", "sigma_fraction": [0.05]}]
  })");
  const auto made =
      testing::run_cli("stimuli " + experiment.string() + " -o " + (dir / "set").string());
  EXPECT_EQ(made.exit_code, 0) << made.output;
  return dir / "set";
}

using Rows = std::vector<std::map<std::string, std::string>>;
Rows read_rows(const fs::path& file) {
  const CsvTable table = parse_csv(testing::read_file(file), file.string());
  Rows rows;
  for (size_t r = 1; r < table.rows.size(); ++r) {
    std::map<std::string, std::string> row;
    for (size_t c = 0; c < table.rows[0].size(); ++c) row[table.rows[0][c]] = table.rows[r][c];
    rows.push_back(row);
  }
  return rows;
}

TEST(PredictCli, EveryImageIsWhatObserveSaysAndEachLevelIsReachedOnItsMix) {
  testing::TempDir dir;
  const fs::path set = small_set(dir.path());
  const auto run = testing::run_cli("predict " + (set / "manifest.json").string() + " -o " +
                                    (dir / "predicted").string() + " --ppd 20 --jobs 2");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const Rows images = read_rows(dir / "predicted/predicted_jnd.csv");
  ASSERT_EQ(images.size(), 10u);
  std::map<double, double> edge_jnd;  // λ → JND of the Cornsweet edge
  for (const auto& row : images) {
    const double lambda = std::stod(row.at("lambda")), jnd = std::stod(row.at("jnd"));
    const std::string folder =
        row.at("method") == "usm3d" ? "usm3d/sigma-0.05" : "cornsweet-image/sigma-3";
    const auto seen = testing::run_cli(
        "observe " + (set / "grey/reference.png").string() + " " +
        (set / "grey" / folder / ("lambda-" + row.at("lambda") + ".png")).string() + " --ppd 20");
    EXPECT_NEAR(jnd, jnd_of(seen.output), 1e-3 * std::max(1.0, jnd))
        << row.at("method") << " " << lambda;
    if (row.at("method") != "usm3d") edge_jnd[lambda] = jnd;
  }
  ASSERT_GT(edge_jnd.rbegin()->second, 4) << "the grid must reach every level for this test";
  const Rows levels = read_rows(dir / "predicted/predicted_thresholds.csv");
  ASSERT_EQ(levels.size(), 2u);
  const auto& edge = levels[0].at("method") == "usm3d" ? levels[1] : levels[0];
  const auto& control = levels[0].at("method") == "usm3d" ? levels[0] : levels[1];
  EXPECT_EQ(control.at("lambda_1jnd"), "");
  EXPECT_EQ(control.at("jnd_at_lambda_max"), "0");
  // Each level: the two neighbouring images mixed in luminance at the predicted λ, and observed.
  const CalibratedDisplay display = srgb_display(100);
  const LuminanceImage reference = read_luminance((set / "grey/reference.png").string(), display);
  Image ref_pfm(reference.width, reference.height, 1);
  for (size_t i = 0; i < reference.cd_m2.size(); ++i) ref_pfm.pixels[i] = float(reference.cd_m2[i]);
  write_image(dir / "reference.pfm", ref_pfm);
  for (const auto& [key, level] :
       {std::pair{"lambda_1jnd", 1.0}, {"lambda_2jnd", 2.0}, {"lambda_4jnd", 4.0}}) {
    const double lambda = std::stod(edge.at(key));
    const double step = 0.25, below = std::floor(lambda / step) * step;
    auto luminance_at = [&](double l) {
      const fs::path file =
          set / "grey/cornsweet-image/sigma-3" / ("lambda-" + format_value(l) + ".png");
      return read_luminance(file.string(), display);
    };
    const LuminanceImage a = luminance_at(below), b = luminance_at(below + step);
    const double t = (lambda - below) / step;
    Image mix(a.width, a.height, 1);
    for (size_t i = 0; i < a.cd_m2.size(); ++i)
      mix.pixels[i] = float(a.cd_m2[i] + t * (b.cd_m2[i] - a.cd_m2[i]));
    write_image(dir / "mix.pfm", mix);
    const auto seen = testing::run_cli("observe " + (dir / "reference.pfm").string() + " " +
                                       (dir / "mix.pfm").string() + " --ppd 20");
    EXPECT_NEAR(jnd_of(seen.output), level, 2e-3 * level) << key << " at λ " << lambda;
  }
  const std::string report = testing::read_file(dir / "predicted/report.html");
  EXPECT_NE(report.find("<svg"), std::string::npos);
  EXPECT_NE(report.find("no response at any λ"), std::string::npos);
  // The audit's bracket check on the same set: with a grid step of 0.25 the edge's threshold has
  // fewer than three steps below it; the control passes.
  const auto audited = testing::run_cli("audit " + (set / "manifest.json").string() + " -o " +
                                        (dir / "audit").string() + " --ppd 20");
  ASSERT_EQ(audited.exit_code, 0) << audited.output;
  const std::string checks = testing::read_file(dir / "audit/checks.csv");
  EXPECT_NE(
      checks.find("the grid brackets the predicted thresholds,grey,cornsweet-image sigma 3,false"),
      std::string::npos)
      << checks;
  EXPECT_NE(checks.find("a control: no predicted response at any λ"), std::string::npos) << checks;
}

TEST(PredictCli, BadInputIsOneLineAndExitTwo) {
  testing::TempDir dir;
  const fs::path set = small_set(dir.path());
  const std::string manifest = (set / "manifest.json").string();
  testing::write_file(dir / "display.json", R"({"screen": {"width_mm": 500}})");
  std::vector<std::pair<testing::CommandResult, std::string>> cases = {
      {testing::run_cli("predict " + manifest + " -o " + (dir / "p").string()), "--ppd"},
      {testing::run_cli("predict " + manifest + " -o " + (dir / "p").string() + " --display " +
                        (dir / "display.json").string()),
       "display.json"},
  };
  fs::remove(set / "grey/cornsweet-image/sigma-3/lambda-0.5.png");
  cases.push_back(
      {testing::run_cli("predict " + manifest + " -o " + (dir / "p").string() + " --ppd 20"),
       "lambda-0.5.png"});
  for (const auto& [run, named] : cases) {
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_EQ(testing::count_lines(run.output), 1) << run.output;
    EXPECT_NE(run.output.find(named), std::string::npos) << run.output;
  }
  EXPECT_FALSE(fs::exists(dir / "p/predicted_thresholds.csv"));
}

}  // namespace
}  // namespace countershade::observer
