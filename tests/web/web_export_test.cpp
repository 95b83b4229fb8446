// The web export: the browser plans the app's trials for every subject and seed, an exported
// study shows both stimuli pixel for pixel in headless Chromium at device scale factors 1, 1.25
// and 2, the browser-side logic passes its own tests, and a set with a missing or altered image is
// refused.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "../adjust/tiny_set.h"
#include "adjust/procedure.h"
#include "adjust/study.h"
#include "core/image.h"

namespace countershade::adjust {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string node(const std::string& arguments) { return "cd " + testing::source_dir().string() + " && node " + arguments; }

json plan_case(const std::vector<int>& grid_sizes, PlanSettings s, uint64_t study_seed, const std::string& subject, int session) {
  std::vector<Condition> conditions;
  for (int g : grid_sizes) conditions.push_back({"scene", "method", 0.1, g});
  s.seed = session_seed(study_seed, subject, session);
  json plan = json::array();
  for (const Trial& t : plan_trials(conditions, s))
    plan.push_back({{"number", t.number}, {"practice", t.practice}, {"condition", t.condition}, {"repetition", t.repetition},
                    {"side", side_name(t.side)}, {"start", {t.start_index[0], t.start_index[1], t.start_index[2]}}});
  return {{"grid_sizes", grid_sizes}, {"study_seed", std::to_string(study_seed)}, {"subject", subject}, {"session", session},
          {"session_seed", std::to_string(s.seed)}, {"repetitions", s.repetitions}, {"side", side_name(s.side)},
          {"start", s.start == StartMode::zero ? "zero" : "random"}, {"practice_trials", s.practice_trials},
          {"practice_conditions", s.practice_conditions}, {"plan", plan}};
}

TEST(WebExport, TheBrowserPlansTheAppsTrialsRowForRow) {
  testing::TempDir dir;
  json cases = json::array();
  PlanSettings counterbalanced;
  counterbalanced.repetitions = 3;
  counterbalanced.practice_trials = 4;
  cases.push_back(plan_case({11, 6, 61, 7}, counterbalanced, 1970, "P01", 1));
  cases.push_back(plan_case({11, 6, 61, 7}, counterbalanced, 1970, "P02", 1));
  cases.push_back(plan_case({11, 6, 61, 7}, counterbalanced, (1ull << 63) + 12345, "sim-3_b", 7));  // beyond 2^53
  PlanSettings fixed;
  fixed.side = Side::left;
  fixed.start = StartMode::zero;
  fixed.repetitions = 2;
  fixed.practice_trials = 3;
  fixed.practice_conditions = {2, 0};
  cases.push_back(plan_case({5, 9, 13}, fixed, 5, "Z", 99));
  testing::write_file(dir / "cases.json", cases.dump());
  const auto run = testing::run_program("bash -c", "'" + node("web/tools/check-plan.mjs " + (dir / "cases.json").string()) + "'");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("4 plans"), std::string::npos) << run.output;
}

TEST(WebExport, TheBrowserLogicPassesItsTests) {
  const auto run = testing::run_program("bash -c", "'" + node("--test web/test/") + "'");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("# fail 0"), std::string::npos) << run.output;
}

// At each device scale factor, the screenshot holds both stimulus PNGs exactly, at the device
// pixel positions the page reports.
TEST(WebExport, BothStimuliArePixelExactAtEveryDeviceScaleFactor) {
  testing::TempDir dir;
  const fs::path manifest = testing::make_tiny_set(dir);
  const auto exported = testing::run_cli("export-web " + manifest.string() + " -o " + (dir / "web").string());
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  for (const char* dpr : {"1", "1.25", "2"}) {
    const fs::path shot = dir / (std::string("shot-") + dpr + ".png");
    const auto run = testing::run_program("bash -c", "'" + node("web/tools/browser-shot.mjs " + (dir / "web").string() + " " + dpr +
                                                                " " + shot.string()) + "'");
    ASSERT_EQ(run.exit_code, 0) << dpr << ": " << run.output;
    const json info = json::parse(testing::read_file(shot.string() + ".json"));
    const Image screen = read_image(shot);
    EXPECT_GE(info["lambda_index"].get<int>(), 1) << dpr;
    for (const char* side : {"left", "right"}) {
      const Image stimulus = read_image(dir / "web" / info[side]["file"].get<std::string>());
      const int x0 = info[side]["x"], y0 = info[side]["y"];
      long differing = 0;
      for (int y = 0; y < stimulus.height; ++y)
        for (int x = 0; x < stimulus.width; ++x)
          for (int c = 0; c < 3; ++c)
            differing += std::lround(stimulus.at(x, y, c) * 255) != std::lround(screen.at(x0 + x, y0 + y, c) * 255);
      EXPECT_EQ(differing, 0) << "device scale factor " << dpr << ", " << side << " at " << x0 << "," << y0;
    }
  }
}

TEST(WebExport, ASetWithAMissingOrAlteredImageIsRefused) {
  testing::TempDir dir;
  const fs::path manifest = testing::make_tiny_set(dir);
  const fs::path image = dir / "set/front/reference.png";
  std::string bytes = testing::read_file(image);
  bytes[bytes.size() / 2] ^= 1;
  testing::write_file(image, bytes);
  auto run = testing::run_cli("export-web " + manifest.string() + " -o " + (dir / "web").string());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("reference.png"), std::string::npos) << run.output;
  EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
  fs::remove(image);
  run = testing::run_cli("export-web " + manifest.string() + " -o " + (dir / "web").string());
  EXPECT_EQ(run.exit_code, 2) << run.output;
  EXPECT_NE(run.output.find("reference.png"), std::string::npos) << run.output;
  EXPECT_FALSE(fs::exists(dir / "web/study.js"));
}

}  // namespace
}  // namespace countershade::adjust
