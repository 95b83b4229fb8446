// The web export: the browser plans the app's trials for every subject and seed, an exported
// study shows both stimuli pixel for pixel in headless Chromium at device scale factors 1, 1.25
// and 2, the browser-side logic passes its own tests, and a set with a missing or altered image is
// refused.

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <random>
#include <set>

#include "../adjust/tiny_set.h"
#include "../adjust/x_display.h"
#include "adjust/procedure.h"
#include "browser_sessions.h"
#include "core/image.h"
#include "formats/responses.h"
#include "runtime/study.h"
#include "screen_pixels.h"

namespace countershade::adjust {
namespace {

// From the study runtime (src/runtime).
using runtime::session_seed;
using testing::app_session;
using testing::browser_session;
using testing::comparable_rows;
using testing::node;

namespace fs = std::filesystem;
using nlohmann::json;

json plan_case(const std::vector<int>& grid_sizes, PlanSettings s, uint64_t study_seed,
               const std::string& subject, int session) {
  std::vector<Condition> conditions;
  for (int g : grid_sizes) conditions.push_back({"scene", "method", 0.1, g});
  s.seed = session_seed(study_seed, subject, session);
  json plan = json::array();
  for (const Trial& t : plan_trials(conditions, s))
    plan.push_back({{"number", t.number},
                    {"practice", t.practice},
                    {"condition", t.condition},
                    {"repetition", t.repetition},
                    {"side", side_name(t.side)},
                    {"start", {t.start_index[0], t.start_index[1], t.start_index[2]}}});
  return {{"grid_sizes", grid_sizes},
          {"study_seed", std::to_string(study_seed)},
          {"subject", subject},
          {"session", session},
          {"session_seed", std::to_string(s.seed)},
          {"repetitions", s.repetitions},
          {"side", side_name(s.side)},
          {"start", s.start == StartMode::zero ? "zero" : "random"},
          {"practice_trials", s.practice_trials},
          {"practice_conditions", s.practice_conditions},
          {"plan", plan}};
}

TEST(WebExport, TheBrowserPlansTheAppsTrialsRowForRow) {
  testing::TempDir dir;
  json cases = json::array();
  PlanSettings counterbalanced;
  counterbalanced.repetitions = 3;
  counterbalanced.practice_trials = 4;
  cases.push_back(plan_case({11, 6, 61, 7}, counterbalanced, 1970, "P01", 1));
  cases.push_back(plan_case({11, 6, 61, 7}, counterbalanced, 1970, "P02", 1));
  cases.push_back(plan_case({11, 6, 61, 7}, counterbalanced, (1ull << 63) + 12345, "sim-3_b",
                            7));  // beyond 2^53
  PlanSettings fixed;
  fixed.side = Side::left;
  fixed.start = StartMode::zero;
  fixed.repetitions = 2;
  fixed.practice_trials = 3;
  fixed.practice_conditions = {2, 0};
  cases.push_back(plan_case({5, 9, 13}, fixed, 5, "Z", 99));
  testing::write_file(dir / "cases.json", cases.dump());
  const auto run = testing::run_program(
      "bash -c", "'" + node("web/tools/check-plan.mjs " + (dir / "cases.json").string()) + "'");
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
  const auto exported =
      testing::run_cli("export-web " + manifest.string() + " -o " + (dir / "web").string());
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  for (const char* dpr : {"1", "1.25", "2"}) {
    const fs::path shot = dir / (std::string("shot-") + dpr + ".png");
    const auto run = testing::run_program(
        "bash -c", "'" +
                       node("web/tools/browser-shot.mjs " + (dir / "web").string() + " " + dpr +
                            " " + shot.string()) +
                       "'");
    ASSERT_EQ(run.exit_code, 0) << dpr << ": " << run.output;
    const json info = json::parse(testing::read_file(shot.string() + ".json"));
    const Image screen = read_image(shot);
    EXPECT_GE(info["lambda_index"].get<int>(), 1) << dpr;
    for (const char* side : {"left", "right"}) {
      const Image stimulus = read_image(dir / "web" / info[side]["file"].get<std::string>());
      const int x0 = info[side]["x"], y0 = info[side]["y"];
      EXPECT_EQ(testing::differing_codes(stimulus, screen, x0, y0), 0)
          << "device scale factor " << dpr << ", " << side << " at " << x0 << "," << y0;
    }
  }
}

// Ten reloads at random moments lose and repeat no answer, and a server that refuses the first two
// POSTs of every row still receives every row exactly once, in order.
TEST(WebExport, ReloadsLoseNothingAndEveryRowIsPostedOnceInOrder) {
  testing::TempDir dir;
  const fs::path manifest = testing::make_tiny_set(dir, R"({"repetitions": 2})");  // 24 answers
  ASSERT_NO_FATAL_FAILURE(testing::export_web(manifest, dir / "web", "--post-url /collect"));
  std::mt19937 random(46);
  std::set<int> points;
  while (points.size() < 10) points.insert(std::uniform_int_distribution<int>(1, 23)(random));
  std::string reloads;
  for (int p : points) reloads += std::to_string(p) + " ";
  fs::create_directories(dir / "browser");
  const fs::path csv = browser_session(dir / "web", dir / "browser", "P09", "9", reloads, 2);
  app_session(manifest, dir / "app", "P09", "9");
  const auto rows = comparable_rows(csv);
  EXPECT_EQ(rows.size(), 1u + 24u);
  EXPECT_EQ(rows, comparable_rows(dir / "app/P09_s01.csv"));
  const std::string table = testing::read_file(csv);
  EXPECT_EQ(testing::read_file(csv.string() + ".posted"), table.substr(table.find('\n') + 1));
}

// The page's last line says whether the study's server has every answer: while the server fails
// (503) it counts the answers still being sent and asks the participant to keep the page open or
// to send the file; where it refuses the rows themselves (422) it asks for the file; once every
// row is acknowledged it says that all answers are saved.
TEST(WebExport, TheEndSaysWhetherTheServerHasEveryAnswer) {
  testing::TempDir dir;
  const fs::path manifest = testing::make_tiny_set(dir);
  ASSERT_NO_FATAL_FAILURE(testing::export_web(manifest, dir / "web", "--post-url /collect"));
  // The page's last line with every row refused with `status`; the rows in the session's CSV.
  const auto refused_end = [&](int status, std::string& rows) {
    const fs::path out = dir / ("refused-" + std::to_string(status));
    fs::create_directories(out);
    const fs::path csv = out / "P01_s01.csv";
    const auto run = testing::run_program(
        "bash -c", "'" +
                       node("web/tools/browser-session.mjs " + (dir / "web").string() + " P01 1 " +
                                csv.string(),
                            "REFUSE=all REFUSE_STATUS=" + std::to_string(status)) +
                       "'");
    EXPECT_EQ(run.exit_code, 0) << run.output;
    rows = std::to_string(testing::count_lines(testing::read_file(csv)) - 1);
    return testing::read_file(csv.string() + ".end");
  };
  std::string rows;
  const std::string failing = refused_end(503, rows);
  EXPECT_NE(failing.find(rows + " answers are still being sent"), std::string::npos) << failing;
  EXPECT_NE(failing.find("keep this page open"), std::string::npos) << failing;
  EXPECT_EQ(failing.find("All answers are saved"), std::string::npos) << failing;
  const std::string refusing = refused_end(422, rows);
  EXPECT_NE(refusing.find("did not accept " + rows + " answers (HTTP 422)"), std::string::npos)
      << refusing;
  EXPECT_NE(refusing.find("download them and send the file"), std::string::npos) << refusing;
  EXPECT_EQ(refusing.find("keep this page open"), std::string::npos) << refusing;
  // Each row refused twice (503) before it is taken: saved in the end.
  fs::create_directories(dir / "sent");
  const fs::path sent = browser_session(dir / "web", dir / "sent", "P02", "2", "", 2);
  EXPECT_NE(testing::read_file(sent.string() + ".end-sent").find("All answers are saved"),
            std::string::npos);
}

// The virtual chinrest, gone through as a participant would (a card dragged larger, five
// blind-spot runs): every row records the px/mm and viewing distance that its formulas give from
// what the participant did, the page is never rescaled, and a reload does not ask again.
TEST(WebExport, TheChinrestIsRecordedInEveryRowAndNotAskedForAgainAfterAReload) {
  testing::TempDir dir;
  const fs::path manifest = testing::make_tiny_set(dir);
  ASSERT_NO_FATAL_FAILURE(testing::export_web(manifest, dir / "web", "--chinrest"));
  const fs::path csv = dir / "chinrest.csv";
  const auto run = testing::run_program(
      "bash -c",
      "'" +
          node("web/tools/browser-chinrest.mjs " + (dir / "web").string() + " 5 " + csv.string()) +
          "'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const json page = json::parse(run.output);
  EXPECT_FALSE(page["asked_again"].get<bool>());
  EXPECT_EQ(page["transform"], "");
  // The plugin's definitions: a credit card is 85.6 mm wide; the blind spot lies 13.5° from
  // fixation.
  auto round2 = [](double v) { return std::round(v * 100) / 100; };
  const double px_per_mm = round2(page["card_px"].get<double>() / 85.6);
  double ball = 0;
  for (const auto& x : page["ball_x"]) ball += x.get<double>() / double(page["ball_x"].size());
  const double distance =
      (page["square_x"].get<double>() - round2(ball)) / px_per_mm / std::tan(13.5 * M_PI / 180);
  ASSERT_GT(distance, 0);
  const auto table = parse_csv(testing::read_file(csv), csv.string());
  ASSERT_EQ(table.rows.size(), 1u + 12u);  // four conditions × three questions
  const auto& header = table.rows[0];
  const size_t mm =
      size_t(std::find(header.begin(), header.end(), "css_px_per_mm") - header.begin());
  const size_t view =
      size_t(std::find(header.begin(), header.end(), "viewing_distance_mm") - header.begin());
  ASSERT_LT(view, header.size());
  for (size_t r = 1; r < table.rows.size(); ++r) {
    EXPECT_DOUBLE_EQ(std::stod(table.rows[r][mm]), px_per_mm) << r;
    EXPECT_NEAR(std::stod(table.rows[r][view]), distance, 0.01) << r;
  }
}

// Text from the set goes into the page as text: markup in an instruction shows as written and no
// script in it runs.
TEST(WebExport, MarkupInTheSetsTextsShowsAsText) {
  testing::TempDir dir;
  const std::string welcome = "<b>bold</b><script>window.injected = 1</script> & \\u2028";
  const fs::path manifest =
      testing::make_tiny_set(dir, R"({"instructions": {"welcome": ")" + welcome + R"("}})");
  ASSERT_EQ(testing::run_cli("export-web " + manifest.string() + " -o " + (dir / "web").string())
                .exit_code,
            0);
  const auto run = testing::run_program(
      "bash -c", "'" + node("web/tools/browser-welcome.mjs " + (dir / "web").string()) + "'");
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const json page = json::parse(run.output);
  EXPECT_EQ(page["text"], "<b>bold</b><script>window.injected = 1</script> & \u2028");
  EXPECT_TRUE(page["injected"].is_null());
  EXPECT_EQ(page["bold"], 0);
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

// A browser shows 8 bits: a 16-bit set is refused rather than shown rounded without a word.
// A 16-bit set goes to the page as its codes: each image's .rgb16 file holds its PNG's 16-bit
// values, RGB, little-endian, top row first (the page's WebGL2 dither reads them).
TEST(WebExport, ASixteenBitSetIsExportedAsItsCodes) {
  testing::TempDir dir;
  const fs::path manifest =
      testing::make_tiny_set(dir, "", 96, 72, 0.4, R"("output": {"bits": 16},)");
  const auto run =
      testing::run_cli("export-web " + manifest.string() + " -o " + (dir / "web").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const std::string page = testing::read_file(dir / "web/study.js");
  EXPECT_NE(page.find("\"bits\": 16"), std::string::npos);
  const runtime::Study study = runtime::load_study(manifest, std::nullopt);
  for (size_t i : {size_t(0), study.images.size() - 1}) {
    char name[32];
    std::snprintf(name, sizeof name, "images/%05zu.rgb16", i + 1);
    const std::string codes = testing::read_file(dir / "web" / name);
    const Image png = read_image(study.images[i].file);
    ASSERT_EQ(codes.size(), size_t(png.width) * size_t(png.height) * 6) << name;
    long differing = 0;
    for (int y = 0; y < png.height; ++y)
      for (int x = 0; x < png.width; ++x)
        for (int c = 0; c < 3; ++c) {
          const size_t at = ((size_t(y) * size_t(png.width) + size_t(x)) * 3 + size_t(c)) * 2;
          const long value = long(uint8_t(codes[at])) | long(uint8_t(codes[at + 1])) << 8;
          differing += value != std::lround(png.at(x, y, c) * 65535.0f);
        }
    EXPECT_EQ(differing, 0) << name;
  }
}

}  // namespace
}  // namespace countershade::adjust
