// Display calibration: the gamma fits of every gun against R psyphy's and the least-squares optima
// of PsychoPy's models (tests/reference/display), the lookup table a scene reads back, and the
// refusal of bad readings.

#include "analysis/display_calibration.h"

#include <gtest/gtest.h>

#include "core/image.h"
#include "core/json_reader.h"
#include "render/scene.h"
#include "render/scene_loader.h"
#include "test_util.h"

namespace countershade::analysis {
namespace {

namespace fs = std::filesystem;

const GammaFit& model(const std::vector<GammaFit>& fits, const std::string& name) {
  for (const GammaFit& f : fits)
    if (f.model == name) return f;
  throw std::runtime_error("no fit " + name);
}

void expect_relative(double got, double expected, double tolerance, const std::string& what) {
  EXPECT_LE(std::abs(got - expected), tolerance * std::abs(expected))
      << what << ": " << got << " against " << expected;
}

// Every gun and model: each parameter within 1e-6 relative, the rss within 1e-8 relative, the
// standard errors of psyphy's model within 1e-6 relative.
TEST(DisplayCalibration, EveryGunsFitsMatchTheReference) {
  const GunReadings guns =
      read_photometer_readings(testing::reference_path("display/calibration_rgb.csv"), 8);
  const nlohmann::json expected =
      parse_json_file(testing::reference_path("display/calibration_rgb.expected.json"));
  ASSERT_EQ(guns.size(), 4u);
  for (const auto& [gun, readings] : guns) {
    const std::vector<GammaFit> fits = fit_gamma_models(readings);
    const auto& e = expected["guns"][gun];
    const GammaFit& psyphy = model(fits, "psyphy");
    for (const char* p : {"Blev", "k", "gamm"}) {
      expect_relative(psyphy.params.at(p), e["ss_calib"][p], 1e-6, gun + " psyphy " + p);
      expect_relative(psyphy.se.at(p), e["ss_calib"]["se"][p], 1e-6, gun + " psyphy se " + p);
    }
    expect_relative(psyphy.rss, e["ss_calib"]["rss"], 1e-8, gun + " psyphy rss");
    const std::pair<const char*, const char*> models[] = {
        {"psychopy-eq1", "eq1"}, {"psychopy-eq2", "eq2"}, {"pelli-zhang", "eq4"}};
    for (const auto& [ours, theirs] : models) {
      const GammaFit& f = model(fits, ours);
      const auto& r = e["psychopy"][theirs];
      for (const auto& [name, value] : f.params)
        expect_relative(value, r[name], 1e-6, gun + " " + ours + " " + name);
      expect_relative(f.rss, r["rss"], 1e-8, gun + " " + ours + " rss");
    }
  }
}

TEST(DisplayCalibration, TheLookupTableRoundTripsEveryCodeValueInAScene) {
  testing::TempDir dir;
  const auto r = testing::run_cli("calibrate " +
                                  testing::reference_path("display/calibration_rgb.csv").string() +
                                  " -o " + (dir / "lab.json").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"lab.lut.csv", "lab-R.svg", "lab-W.svg"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  const nlohmann::json display = parse_json_file(dir / "lab.json");
  EXPECT_EQ(display["lookup_table_from"], "W, psyphy fit");
  const nlohmann::json expected =
      parse_json_file(testing::reference_path("display/calibration_rgb.expected.json"));
  expect_relative(display["fits"]["W"]["psyphy"]["gamm"], expected["guns"]["W"]["ss_calib"]["gamm"],
                  1e-6, "W gamm");
  testing::write_file(dir / "scene.json", R"({"version": 1,
    "camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "fov": 30, "width": 8, "height": 8},
    "display": {"calibration": "lab.json"},
    "objects": [{"shape": {"type": "sphere"}}], "lights": [{"type": "ambient", "radiance": 1}]})");
  const Scene scene = load_scene(dir / "scene.json");
  ASSERT_TRUE(scene.display.luminance_cd_m2);
  const auto& w = expected["guns"]["W"]["ss_calib"];
  expect_relative(scene.display.luminance_cd_m2->first, w["Blev"], 1e-6, "black");
  expect_relative(scene.display.luminance_cd_m2->second,
                  w["Blev"].get<double>() + w["k"].get<double>(), 1e-6, "white");
  int wrong = 0;
  for (int code = 0; code <= 255; ++code) {
    const double value = code / 255.0;
    wrong += scene.display.encoding.encode(scene.display.encoding.decode(value)) != value;
  }
  EXPECT_EQ(wrong, 0);
  // Relative luminance at half scale is (0.5^γ): the table follows the fit, not a default gamma.
  const double gamm = w["gamm"];
  EXPECT_NEAR(scene.display.encoding.decode(128 / 255.0), std::pow(128 / 255.0, gamm), 1e-9);
}

// A set made for the calibrated display decodes with its table, and the audit gives each image's
// mean luminance: black + mean relative luminance (Rec. 709 weights of the decoded channels) ×
// (white − black), computed here from the PNG.
TEST(DisplayCalibration, TheAuditReportsMeanLuminanceOnACalibratedDisplay) {
  testing::TempDir dir;
  ASSERT_EQ(testing::run_cli("calibrate " +
                             testing::reference_path("display/calibration_rgb.csv").string() +
                             " -o " + (dir / "lab.json").string())
                .exit_code,
            0);
  testing::write_file(dir / "scene.json", R"({"version": 1,
    "camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "fov": 30, "width": 32, "height": 24},
    "render": {"spp": 2}, "display": {"calibration": "lab.json"},
    "objects": [{"shape": {"type": "sphere"}}], "lights": [{"type": "directional", "direction": [1, 1, 1], "irradiance": 1}]})");
  testing::write_file(dir / "e.json", R"({"version": 1, "lambda": {"min": 0, "max": 1, "step": 1},
    "scenes": [{"name": "ball", "file": "scene.json"}], "methods": [{"method": "usm2d", "sigma_px": [2]}]})");
  ASSERT_EQ(
      testing::run_cli("stimuli " + (dir / "e.json").string() + " -o " + (dir / "set").string())
          .exit_code,
      0);
  ASSERT_EQ(testing::run_cli("audit " + (dir / "set/manifest.json").string() + " -o " +
                             (dir / "audit").string())
                .exit_code,
            0);
  const nlohmann::json audit = parse_json_file(dir / "audit/audit.json");
  const Scene scene = load_scene(dir / "scene.json");
  const auto [black, white] = *scene.display.luminance_cd_m2;
  int checked = 0;
  for (const auto& s : audit["stimuli"]) {
    const Image image = read_image(dir / "set" / s["file"].get<std::string>());
    double y = 0;
    for (size_t p = 0; p < image.pixels.size() / 3; ++p) {
      const float* c = &image.pixels[3 * p];
      y += 0.2126 * scene.display.encoding.decode(c[0]) +
           0.7152 * scene.display.encoding.decode(c[1]) +
           0.0722 * scene.display.encoding.decode(c[2]);
    }
    const double expected = black + y / double(image.pixels.size() / 3) * (white - black);
    EXPECT_NEAR(s["mean_luminance_cd_m2"].get<double>(), expected, 1e-3 * expected) << s["file"];
    ++checked;
  }
  EXPECT_EQ(checked, 3);
}

TEST(DisplayCalibration, BadReadingsAreRefusedInOneLine) {
  testing::TempDir dir;
  auto refused = [&](const std::string& csv, const std::string& expected,
                     const std::string& flags = "") {
    testing::write_file(dir / "r.csv", csv);
    const auto r = testing::run_cli("calibrate " + (dir / "r.csv").string() + " -o " +
                                    (dir / "d.json").string() + flags);
    EXPECT_EQ(r.exit_code, 2) << csv << r.output;
    EXPECT_EQ(testing::count_lines(r.output), 1) << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir / "d.json"));
  };
  const std::string header = "gun,code_value,lum_cd_m2\n";
  refused(header + "W,0,1\nW,85,10\nW,170,8\nW,255,50\n",
          "gun W: luminance does not rise with the level");
  refused(header + "W,0,1\nW,128,10\nW,255,50\n", "gun W: 3 readings; at least 4 are needed");
  refused(header + "W,0,-1\nW,85,10\nW,170,20\nW,255,50\n",
          "line 2: lum_cd_m2: a luminance cannot be negative");
  refused(header + "W,0,1\nW,85,10\nW,170,20\nW,256,50\n",
          "line 5: code_value: 256 is not a level from 0 to 255");
  refused(header + "W,0,1\nW,85,10\nW,170,20\nW,1023,50\n",
          "code_value: 1023 is not a level from 0 to 511", " --bits 9");
  refused(header + "X,0,1\n", "gun: expected R, G, B or W, got 'X'");
  refused("gun,level,lum\nW,0,1\n",
          "expected the columns gun, lum_cd_m2 and code_value or gl (or both)");
  const std::string both = "gun,code_value,gl,lum_cd_m2\n";
  refused(both + "W,0,0,1\nW,85,0.333333,10\nW,170,0.5,20\nW,255,1,50\n",
          "line 4: gl 0.5 does not match code_value 170 (170/255 = 0.666667 at --bits 8)");
  refused(both + "W,0,0,1\nW,85,0.333333,10\nW,170,0.666667,20\nW,255,1.5,50\n",
          "line 5: gl: 1.5 is not a level from 0 to 1");
}

// Photometer exports often carry both code_value and gl: they are read when they agree, and give
// the very readings code_value alone gives.
TEST(DisplayCalibration, ReadingsWithBothCodeValueAndGlAgreeingAreRead) {
  testing::TempDir dir;
  const GunReadings reference =
      read_photometer_readings(testing::reference_path("display/calibration_rgb.csv"), 8);
  std::string code_only = "gun,code_value,lum_cd_m2\n", both = "gun,code_value,gl,lum_cd_m2\n";
  for (const auto& [gun, readings] : reference)
    for (const Reading& r : readings) {
      const int code = int(std::lround(r.level * 255));
      char luminance[32], gl[32];
      std::snprintf(luminance, sizeof luminance, "%.17g", r.luminance);
      std::snprintf(gl, sizeof gl, "%.7f",
                    code / 255.0);  // rounded as exports print it: within 1e-6
      code_only += gun + "," + std::to_string(code) + "," + luminance + "\n";
      both += gun + "," + std::to_string(code) + "," + gl + "," + luminance + "\n";
    }
  const GunReadings expected =
      read_photometer_readings(testing::write_file(dir / "code.csv", code_only), 8);
  const GunReadings got = read_photometer_readings(testing::write_file(dir / "both.csv", both), 8);
  ASSERT_EQ(got.size(), 4u);
  ASSERT_EQ(got.size(), expected.size());
  for (const auto& [gun, readings] : expected) {
    ASSERT_EQ(got.at(gun).size(), readings.size()) << gun;
    ASSERT_GE(readings.size(), 10u) << gun;
    for (size_t i = 0; i < readings.size(); ++i) {
      EXPECT_EQ(got.at(gun)[i].level, readings[i].level) << gun << " " << i;
      EXPECT_EQ(got.at(gun)[i].luminance, readings[i].luminance) << gun << " " << i;
    }
  }
}

}  // namespace
}  // namespace countershade::analysis
