// A forced-choice study in the browser: exported from a set whose experiment has a forced_choice
// block and run in headless Chromium by the simulated observer, it gives the rows of `choose` for
// the same subject and observer (apart from the clock's and the browser's columns) and the same
// psychometric fits; reloads at random moments lose and repeat no trial, and every procedure comes
// back in its state (the rows after a reload are the app's, which were planned from it); every row
// reaches a refusing server once, in order; and a temporal trial whose interval ran long is
// recorded as such and shown again.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <random>
#include <set>

#include "../adjust/tiny_set.h"
#include "../adjust/x_display.h"
#include "core/image.h"
#include "forced_choice/choice_row.h"
#include "formats/responses.h"
#include "screen_pixels.h"

namespace countershade::forced_choice {
namespace {

namespace fs = std::filesystem;

// A tiny set (two scenes × two σ, λ from 0 to 2 in steps of 0.1) with this forced_choice block.
fs::path choice_set(const testing::TempDir& dir, const std::string& block) {
  return testing::make_tiny_set(dir, "", 96, 72, 0.1, "\"forced_choice\": " + block + ",");
}

// The rows of a trials CSV without the clock's columns and the browser's, and without the answers
// to trials shown with a mistimed interval (which were shown again).
std::vector<std::vector<std::string>> comparable_rows(const fs::path& csv) {
  const CsvTable table = parse_csv(testing::read_file(csv), csv.string());
  const auto& header = table.rows.front();
  const size_t timing =
      size_t(std::find(header.begin(), header.end(), "interval_timing") - header.begin());
  std::vector<std::vector<std::string>> rows;
  for (const auto& row : table.rows) {
    if (timing < row.size() && row[timing] == "mistimed") continue;
    std::vector<std::string> kept;
    for (size_t c = 0; c < choice_columns().size(); ++c)
      if (choice_columns()[c] != "rt_ms" && choice_columns()[c] != "time_utc")
        kept.push_back(c < row.size() ? row[c] : "?");
    rows.push_back(kept);
  }
  return rows;
}

// Whether the CSV has a row of trial `number` recorded as shown with a mistimed interval.
bool has_mistimed_row(const fs::path& csv, int number) {
  const CsvTable table = parse_csv(testing::read_file(csv), csv.string());
  const auto& header = table.rows.front();
  const auto column = [&](const char* name) {
    return size_t(std::find(header.begin(), header.end(), name) - header.begin());
  };
  return std::any_of(table.rows.begin() + 1, table.rows.end(), [&](const auto& row) {
    return row.at(column("trial")) == std::to_string(number) &&
           row.at(column("interval_timing")) == "mistimed";
  });
}

// The app's session of `observer`, on the frame clock; returns its CSV.
fs::path app_session(const fs::path& manifest, const fs::path& sessions, const std::string& subject,
                     const std::string& observer) {
  testing::XvfbServer x;
  testing::Child app({COUNTERSHADE_BINARY, "choose", manifest.string(), "--subject", subject,
                      "--sessions", sessions.string(), "--observer", observer, "--frame-clock"},
                     x.display(), (sessions.parent_path() / "app-log.txt").string());
  EXPECT_EQ(app.wait(300), 0) << testing::read_file(sessions.parent_path() / "app-log.txt");
  return sessions / (subject + "_s01.forced-choice.csv");
}

// What a browser session does besides answering: reload after these numbers of answers, hold
// this trial's first interval once (0: none).
struct Faults {
  std::string reloads;
  int stall_trial = 0;
};

// The browser's session; returns its CSV. Its server refuses every row's first POST; the rows it
// took are in CSV.posted.
fs::path browser_session(const fs::path& study, const fs::path& out, const std::string& subject,
                         const std::string& observer, const Faults& faults) {
  fs::create_directories(out);
  const fs::path csv = out / (subject + "_s01.forced-choice.csv");
  const auto run = testing::run_program(
      "bash -c", "'cd " + testing::source_dir().string() +
                     " && REFUSE=1 STALL=" + std::to_string(faults.stall_trial) +
                     " node web/tools/browser-session.mjs " + study.string() + " " + subject + " " +
                     observer + " " + csv.string() + " " + faults.reloads + "'");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return csv;
}

// What compare_sessions saw in the app's rows.
struct Compared {
  size_t trials = 0;
  std::set<std::string> procedures;  // the `procedure` column's values
};

// Exports the set's forced-choice study, runs it in the app and in the browser, and compares the
// rows and the psychometric fits.
Compared compare_sessions(const std::string& block, const std::string& observer,
                          const Faults& faults = {}) {
  testing::TempDir dir;
  const fs::path manifest = choice_set(dir, block);
  const auto exported = testing::run_cli("export-web " + manifest.string() + " -o " +
                                         (dir / "web").string() + " --post-url /collect");
  EXPECT_EQ(exported.exit_code, 0) << exported.output;
  EXPECT_NE(exported.output.find("forced-choice study"), std::string::npos) << exported.output;
  const fs::path app = app_session(manifest, dir / "app", "P01", observer);
  const fs::path browser = browser_session(dir / "web", dir / "browser", "P01", observer, faults);
  const auto rows = comparable_rows(app);
  EXPECT_EQ(comparable_rows(browser), rows);
  const std::string posted = testing::read_file(browser);
  EXPECT_EQ(testing::read_file(browser.string() + ".posted"), posted.substr(posted.find('\n') + 1))
      << "every row posted once, in order";
  if (faults.stall_trial > 0) {  // (a busy machine may lose a frame elsewhere too)
    EXPECT_TRUE(has_mistimed_row(browser, faults.stall_trial))
        << "the held trial is recorded as mistimed (and shown again):\n"
        << posted;
  }
  for (const auto& [csv, report] : {std::pair{app, "app-report"}, {browser, "browser-report"}}) {
    const auto analyzed = testing::run_cli("analyze " + csv.string() + " -o " +
                                           (dir / report).string() + " --no-figures");
    EXPECT_EQ(analyzed.exit_code, 0) << analyzed.output;
  }
  const std::string fits = testing::read_file(dir / "app-report/psychometric_fits.csv");
  EXPECT_GT(std::count(fits.begin(), fits.end(), '\n'), 1) << fits;
  EXPECT_EQ(testing::read_file(dir / "browser-report/psychometric_fits.csv"), fits);
  Compared compared{rows.size() - 1, {}};
  const CsvTable table = parse_csv(testing::read_file(app), app.string());
  const auto& header = table.rows.front();
  const size_t column =
      size_t(std::find(header.begin(), header.end(), "procedure") - header.begin());
  for (size_t r = 1; r < table.rows.size(); ++r)
    compared.procedures.insert(table.rows[r].at(column));
  return compared;
}

// A 4AFC spatial trial at device scale factors 1, 1.25 and 2: each of the four images is its PNG
// pixel for pixel at the device-pixel place the page reports, the target the enhanced one.
TEST(WebChoice, EveryAlternativeIsPixelExactAtEveryDeviceScaleFactor) {
  testing::TempDir dir;
  const fs::path manifest = choice_set(
      dir, R"({"n_afc": 4, "procedure": {"type": "constant", "lambdas": [2], "repetitions": 1}})");
  ASSERT_EQ(testing::run_cli("export-web " + manifest.string() + " -o " + (dir / "web").string())
                .exit_code,
            0);
  for (const char* dpr : {"1", "1.25", "2"}) {
    const fs::path shot = dir / (std::string("shot-") + dpr + ".png");
    const auto run = testing::run_program(
        "bash -c", "'cd " + testing::source_dir().string() +
                       " && node web/tools/browser-choice-shot.mjs " + (dir / "web").string() +
                       " " + dpr + " " + shot.string() + "'");
    ASSERT_EQ(run.exit_code, 0) << dpr << ": " << run.output;
    const auto info = nlohmann::json::parse(testing::read_file(shot.string() + ".json"));
    const Image screen = read_image(shot);
    ASSERT_EQ(info["files"].size(), 4u);
    std::set<std::string> shown;
    for (size_t i = 0; i < 4; ++i) {
      const std::string file = info["files"][i];
      shown.insert(file);
      const Image stimulus = read_image(dir / "web" / file);
      EXPECT_EQ(testing::differing_codes(stimulus, screen, info["xs"][i], info["y"]), 0)
          << "device scale factor " << dpr << ", image " << i;
    }
    EXPECT_EQ(shown.size(), 2u) << "three references and one enhanced image";
  }
}

// Asking for a forced-choice study of a set that has none, or for a study that does not exist,
// is one line and exit 2, and writes nothing.
TEST(WebChoice, AStudyTheSetDoesNotHaveIsRefused) {
  testing::TempDir dir;
  const fs::path manifest = testing::make_tiny_set(dir);
  for (const char* study : {"forced-choice", "staircase"}) {
    const auto run = testing::run_cli("export-web " + manifest.string() + " -o " +
                                      (dir / "web").string() + " --study " + study);
    EXPECT_EQ(run.exit_code, 2) << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
    EXPECT_NE(run.output.find(std::string(study) == "staircase" ? "--study" : "forced_choice"),
              std::string::npos)
        << run.output;
    EXPECT_FALSE(fs::exists(dir / "web"));
  }
}

// The page starts every condition's QUEST+ at once in its WebAssembly engine, whose memory ends at
// 2 GiB; the conditions on one grid share one copy of the tables. A study whose procedures would
// need more than half of that is refused at export, with one line and nothing written, though
// this machine would hold them; a grid of a third the size exports.
TEST(WebChoice, ProceduresThatWouldOutgrowTheBrowsersMemoryAreRefusedAtExport) {
  using json = nlohmann::json;
  const auto block = [](int lapse_rates) {  // 100 × 100 × lapse_rates points, 20 stimuli
    json b = json::parse(R"({"type": "questplus", "param_domain": {"lower_asymptote": 0.5}})");
    for (int i = 0; i < 100; ++i) {
      b["param_domain"]["threshold"].push_back(-2 + 0.02 * i);
      b["param_domain"]["slope"].push_back(1 + 0.05 * i);
    }
    for (int i = 0; i < lapse_rates; ++i) b["param_domain"]["lapse_rate"].push_back(1e-4 * i);
    return json{{"procedure", b}}.dump();
  };
  // The tables, 40 doubles a point, and 4 posteriors of one: 44 × 8 × 3,100,000 B = 1.02 GiB.
  testing::TempDir dir;
  const fs::path manifest = choice_set(dir, block(310));
  const auto refused =
      testing::run_cli("export-web " + manifest.string() + " -o " + (dir / "web").string());
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_EQ(std::count(refused.output.begin(), refused.output.end(), '\n'), 1) << refused.output;
  for (const char* part :
       {"experiment.forced_choice.procedure", "4 conditions", "1.02 GiB", "browser"})
    EXPECT_NE(refused.output.find(part), std::string::npos) << part << ": " << refused.output;
  EXPECT_FALSE(fs::exists(dir / "web"));
  testing::TempDir third;
  const auto exported = testing::run_cli("export-web " + choice_set(third, block(100)).string() +
                                         " -o " + (third / "web").string());
  EXPECT_EQ(exported.exit_code, 0) << exported.output;
}

// Every procedure in one spatial session, each condition its own (condition_procedures), with
// practice, feedback and three reloads.
TEST(WebChoice, SpatialSessionOfEveryProcedureGivesTheAppsRowsAndFits) {
  const Compared compared = compare_sessions(R"({"n_afc": 2, "practice_trials": 2,
      "feedback_frames": 2, "max_trials": 8,
      "procedure": {"type": "constant", "lambdas": [0.2, 0.5, 1, 2], "repetitions": 2},
      "condition_procedures": [
        {"scene": "front", "method": "usm3d", "sigma": 0.08, "procedure": {"type": "staircase",
         "startVal": 1, "stepSizes": [4, 2], "nTrials": 8}},
        {"scene": "small", "method": "usm3d", "sigma": 0.03, "procedure": {"type": "quest",
         "tGuess": -0.3, "tGuessSd": 0.6, "pThreshold": 0.82, "beta": 3.5, "delta": 0.01,
         "gamma": 0.5, "nTrials": 8}},
        {"scene": "small", "method": "usm3d", "sigma": 0.08, "procedure": {"type": "questplus",
         "trials": 8, "param_domain": {"threshold": [-1, -0.8, -0.6, -0.4, -0.2, 0, 0.2],
         "slope": [2, 3.5], "lower_asymptote": 0.5, "lapse_rate": [0, 0.02]}}}]})",
                                             "weibull:0.5,3,7", {"3 11 20", 0});
  EXPECT_EQ(compared.trials, 4u * 8u);
  EXPECT_EQ(compared.procedures,
            (std::set<std::string>{"constant", "staircase", "quest", "questplus"}));
}

// Ten reloads of a temporal 3AFC session mixing the procedures, and a trial whose first interval
// the page held for 120 ms: it is recorded as mistimed, shown again, and the rows that count are
// still the app's.
TEST(WebChoice, TemporalSessionSurvivesTenReloadsAndAMistimedInterval) {
  std::mt19937 random(66);
  std::set<int> points;
  while (points.size() < 10) points.insert(std::uniform_int_distribution<int>(1, 23)(random));
  Faults faults{"", 9};
  for (int p : points) faults.reloads += std::to_string(p) + " ";
  const Compared compared = compare_sessions(R"({"n_afc": 3, "layout": "temporal",
      "interval_frames": 2, "blank_frames": 1, "practice_trials": 1, "max_trials": 6,
      "procedure": {"type": "staircase", "startVal": 1, "stepSizes": [4, 2], "nTrials": 6},
      "condition_procedures": [
        {"scene": "front", "method": "usm3d", "sigma": 0.03, "procedure": {"type": "constant",
         "lambdas": [0.5, 1, 2], "repetitions": 2}},
        {"scene": "small", "method": "usm3d", "sigma": 0.03, "procedure": {"type": "quest",
         "tGuess": -0.3, "tGuessSd": 0.6, "pThreshold": 0.75, "beta": 3.5, "delta": 0.01,
         "gamma": 0.3333, "nTrials": 6}},
        {"scene": "small", "method": "usm3d", "sigma": 0.08, "procedure": {"type": "questplus",
         "trials": 6, "param_domain": {"threshold": [-1, -0.6, -0.2, 0.2], "slope": [3.5],
         "lower_asymptote": 0.3333, "lapse_rate": 0.02}}}]})",
                                             "weibull:0.5,3,11", faults);
  EXPECT_EQ(compared.trials, 4u * 6u);
  EXPECT_EQ(compared.procedures,
            (std::set<std::string>{"constant", "staircase", "quest", "questplus"}));
}

}  // namespace
}  // namespace countershade::forced_choice
