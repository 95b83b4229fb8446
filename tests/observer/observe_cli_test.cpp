// `countershade observe` on a ModelFest Gabor shown at its measured threshold on a 30 cd/m²
// field: about 1 JND, twice that at twice the contrast, and the same from 16-bit PNG codes as from
// luminance; the map puts the response where the pattern is; bad input is one line and exit 2.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/color.h"
#include "core/image.h"
#include "observer/modelfest.h"
#include "test_util.h"

namespace countershade::observer {
namespace {

namespace fs = std::filesystem;

constexpr int kSize = 128;
constexpr double kPpd = 120, kMean = 30;

// ModelFest stimulus 12 (4 c/deg, s = 0.14°) at `contrast` on the mean, in cd/m².
Image gabor_luminance(double contrast) {
  const auto stimuli = modelfest_stimuli(kPpd, kSize);
  const auto& s = *std::find_if(stimuli.begin(), stimuli.end(),
                                [](const ModelfestStimulus& m) { return m.number == 12; });
  Image image(kSize, kSize, 1);
  for (size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = float(kMean * (1 + contrast * s.image.values[i]));
  return image;
}

double jnd_of(const testing::CommandResult& run) {
  const auto at = run.output.rfind("jnd ");
  EXPECT_NE(at, std::string::npos) << run.output;
  return at == std::string::npos ? NAN : std::stod(run.output.substr(at + 4));
}

testing::CommandResult observe(const fs::path& reference, const fs::path& test,
                               const std::string& extra = "") {
  return testing::run_cli("observe " + reference.string() + " " + test.string() + " --ppd 120" +
                          extra);
}

TEST(ObserveCli, AModelfestGaborAtItsMeasuredThresholdIsAboutOneJnd) {
  testing::TempDir dir;
  const double threshold = std::pow(10.0, -32.371 / 20);  // ModelFest's stimulus 12
  write_image(dir / "mean.pfm", gabor_luminance(0));
  write_image(dir / "gabor.pfm", gabor_luminance(threshold));
  write_image(dir / "gabor2.pfm", gabor_luminance(2 * threshold));
  const auto once =
      observe(dir / "mean.pfm", dir / "gabor.pfm", " --map " + (dir / "map.png").string());
  ASSERT_EQ(once.exit_code, 0) << once.output;
  const double jnd = jnd_of(once);
  EXPECT_GT(jnd, std::pow(10.0, -1.5 / 20)) << "within the fit's 1.5 dB of 1 JND";
  EXPECT_LT(jnd, std::pow(10.0, 1.5 / 20));
  EXPECT_NEAR(jnd_of(observe(dir / "mean.pfm", dir / "gabor2.pfm")), 2 * jnd, 1e-3 * jnd);
  // 16-bit sRGB codes of the same luminances, at a peak of 100 cd/m².
  for (const char* name : {"mean", "gabor2"}) {
    Image codes = read_image(dir / (std::string(name) + ".pfm"));
    for (float& v : codes.pixels) v = float(srgb_encode(v / 100.0));
    write_image(dir / (std::string(name) + ".png"), codes, {16});
  }
  EXPECT_NEAR(jnd_of(observe(dir / "mean.png", dir / "gabor2.png", " --peak-luminance 100")),
              2 * jnd, 0.01 * jnd);
  // The map's brightest pixel lies on the Gabor's centre bar.
  const Image map = read_image(dir / "map.png");
  size_t brightest = 0;
  for (size_t p = 0; p < size_t(kSize) * kSize; ++p)
    if (map.pixels[p * 3 + 1] > map.pixels[brightest * 3 + 1]) brightest = p;
  EXPECT_NEAR(double(brightest % kSize), kSize / 2, 10);
  EXPECT_NEAR(double(brightest / kSize), kSize / 2, 2);
}

// A display file: its screen gives the pixels per degree (as --ppd would), and its calibration
// the luminance of each code; with a linear table from 0 to 100 cd/m², 16-bit codes c show 100·c.
TEST(ObserveCli, ADisplayFileGivesThePixelsPerDegreeAndTheLuminance) {
  testing::TempDir dir;
  for (const char* name : {"mean", "gabor"}) {
    Image codes = gabor_luminance(name == std::string("gabor") ? 0.02 : 0);
    for (float& v : codes.pixels) v /= 100;
    write_image(dir / (std::string(name) + ".png"), codes, {16});
    for (float& v : codes.pixels) v = float(std::round(v * 65535) / 65535 * 100);
    write_image(dir / (std::string(name) + ".pfm"), codes);
  }
  testing::write_file(dir / "linear.lut.csv", "code,luminance\n0,0\n1,1\n");
  testing::write_file(dir / "linear.json", R"({"display": {"encoding": "lut",
    "lut": "linear.lut.csv"}, "luminance_cd_m2": {"black": 0, "white": 100}})");
  testing::write_file(dir / "lab.json", R"({"screen": {"width_mm": 300, "width_px": 1920,
    "distance_mm": 570}, "calibration": "linear.json"})");
  const double ppd = 2 * 570 * std::tan(0.5 * std::numbers::pi / 180) * 1920 / 300;
  const auto by_file =
      testing::run_cli("observe " + (dir / "mean.png").string() + " " +
                       (dir / "gabor.png").string() + " --display " + (dir / "lab.json").string());
  ASSERT_EQ(by_file.exit_code, 0) << by_file.output;
  const auto by_flags =
      testing::run_cli("observe " + (dir / "mean.pfm").string() + " " +
                       (dir / "gabor.pfm").string() + " --ppd " + std::to_string(ppd));
  EXPECT_NEAR(jnd_of(by_file), jnd_of(by_flags), 1e-4 * jnd_of(by_flags));
  // The display file and the flags it replaces are not given together.
  for (const char* flag : {" --ppd 60", " --peak-luminance 80"}) {
    const auto both = testing::run_cli("observe " + (dir / "mean.png").string() + " " +
                                       (dir / "gabor.png").string() + " --display " +
                                       (dir / "lab.json").string() + flag);
    EXPECT_EQ(both.exit_code, 2) << both.output;
    EXPECT_NE(both.output.find("lab.json"), std::string::npos) << both.output;
  }
}

TEST(ObserveCli, BadInputIsOneLineAndExitTwo) {
  testing::TempDir dir;
  write_image(dir / "mean.pfm", gabor_luminance(0));
  write_image(dir / "small.pfm", Image(64, 64, 1, 30.0f));
  write_image(dir / "black.pfm", Image(kSize, kSize, 1, 0.0f));
  Image nan_pixel(kSize, kSize, 1, 30.0f), negative(kSize, kSize, 1, 30.0f);
  nan_pixel.pixels[77] = NAN;
  negative.pixels[5] = -1;
  write_image(dir / "nan.pfm", nan_pixel);
  write_image(dir / "negative.pfm", negative);
  testing::write_file(dir / "narrow.json", R"({"screen": {"width_mm": -3, "width_px": 1920,
    "distance_mm": 570}})");
  testing::write_file(dir / "uncalibrated.json", R"({"screen": {"width_mm": 300,
    "width_px": 1920, "distance_mm": 570}, "calibration": "gone.json"})");
  const auto with_display = [&](const char* file) {
    return testing::run_cli("observe " + (dir / "mean.pfm").string() + " " +
                            (dir / "mean.pfm").string() + " --display " + (dir / file).string());
  };
  const std::vector<std::pair<testing::CommandResult, std::string>> cases = {
      {observe(dir / "mean.pfm", dir / "nan.pfm"), "nan.pfm"},
      {observe(dir / "mean.pfm", dir / "negative.pfm"), "negative.pfm"},
      {with_display("missing.json"), "missing.json"},
      {with_display("narrow.json"), "width_mm"},
      {with_display("uncalibrated.json"), "gone.json"},
      {observe(dir / "mean.pfm", dir / "small.pfm"), "small.pfm"},
      {observe(dir / "black.pfm", dir / "mean.pfm"), "black.pfm"},
      {observe(dir / "mean.pfm", dir / "missing.pfm"), "missing.pfm"},
      {observe(dir / "mean.pfm", dir / "mean.pfm", " --map " + (dir / "map.txt").string()),
       "map.txt"},
  };
  for (const auto& [run, named] : cases) {
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
    EXPECT_NE(run.output.find(named), std::string::npos) << run.output;
  }
  EXPECT_FALSE(fs::exists(dir / "map.txt"));
}

}  // namespace
}  // namespace countershade::observer
