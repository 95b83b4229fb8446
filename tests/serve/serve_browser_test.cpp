// `countershade serve` end to end, and the browser's parity with the app: three participants in
// headless Chromium on the real page, each by their link, one reloaded twice on the way, the third
// a model observer answering from the prediction the page was exported with. The export holds the
// rows that the app writes for the same subjects and observers, apart from the clock's and the
// browser's columns, and `analyze` gives the same results.json. A forced-choice session is
// followed trial by trial.

#include <gtest/gtest.h>

#include "../web/browser_sessions.h"
#include "served_study.h"

namespace countershade::serve {
namespace {

namespace fs = std::filesystem;

TEST(ServeBrowser, LinkedParticipantsGiveTheAppsRowsThroughTheServer) {
  testing::TempDir dir;
  const fs::path manifest = testing::make_tiny_set(dir);
  ASSERT_NO_FATAL_FAILURE(testing::export_web(manifest, dir / "web", "--model-ppd 40"));
  const fs::path web = dir / "web";
  const fs::path db = dir / "study.sqlite";
  const auto links = testing::make_links(web, db, 3);
  testing::ServerProcess server(web, db);
  fs::create_directories(dir / "browser");
  std::string app_csvs, export_csvs;
  // (the app's observer, the page's): two simulated observers and a model observer at 40 px/°.
  const std::pair<std::string, std::string> observers[] = {
      {"1", "1"}, {"2", "2"}, {"model:3:40", "model:3"}};
  for (int p = 0; p < 3; ++p) {
    const auto& [subject, link] = links[size_t(p)];
    const auto& [app_spec, page_spec] = observers[p];
    testing::browser_session(server.url() + "?link=" + link, dir / "browser", subject, page_spec,
                             p == 1 ? "4 9" : "");
    testing::app_session(manifest, dir / "app", subject, app_spec);
    app_csvs += " " + (dir / "app" / (subject + "_s01.csv")).string();
    export_csvs += " " + (dir / "export" / (subject + "_s01.csv")).string();
  }
  // The export while the server runs.
  const auto exported =
      testing::run_cli("serve --data " + db.string() + " --export " + (dir / "export").string());
  ASSERT_EQ(exported.exit_code, 0) << exported.output;
  for (const auto& [subject, link] : links) {
    const auto app_rows = testing::comparable_rows(dir / "app" / (subject + "_s01.csv"));
    EXPECT_EQ(app_rows.size(), 13u);
    EXPECT_EQ(testing::comparable_rows(dir / "export" / (subject + "_s01.csv")), app_rows)
        << subject;
    // What the page offered for download is what the server kept.
    EXPECT_EQ(testing::read_file(dir / "export" / (subject + "_s01.csv")),
              testing::read_file(dir / "browser" / (subject + "_s01.csv")));
  }
  const auto status = httplib::Client("127.0.0.1", server.port())
                          .Get("/admin/status.json?token=" + server.admin_token());
  ASSERT_TRUE(status);
  EXPECT_EQ(nlohmann::json::parse(status->body)["states"]["completed"], 3) << status->body;
  EXPECT_EQ(server.stop(), 0);
  ASSERT_EQ(testing::run_cli("analyze" + app_csvs + " -o " + (dir / "app-report").string() +
                             " --no-figures")
                .exit_code,
            0);
  const auto served =
      testing::run_cli("analyze" + export_csvs + " -o " + (dir / "served-report").string());
  ASSERT_EQ(served.exit_code, 0) << served.output;
  EXPECT_EQ(testing::read_file(dir / "app-report/results.json"),
            testing::read_file(dir / "served-report/results.json"));
  EXPECT_NE(
      testing::read_file(dir / "served-report/report.html").find("36 answers came from a browser"),
      std::string::npos);
}

// A forced-choice session through the server: the server runs the session's trials alongside the
// page (checking each row is the trial the page shows next), takes a mistimed interval's row
// without moving on, and marks the session completed when the run ends. Restarted, it rebuilds
// the run from the stored rows: a repeat of the last row is acknowledged, and a row after the
// last trial is refused.
TEST(ServeBrowser, AForcedChoiceSessionIsFollowedTrialByTrial) {
  testing::TempDir dir;
  const fs::path manifest = testing::make_tiny_set(dir, "", 96, 72, 0.1, R"("forced_choice": {
      "n_afc": 2, "layout": "temporal", "interval_frames": 2, "blank_frames": 1,
      "practice_trials": 1, "max_trials": 3,
      "procedure": {"type": "staircase", "startVal": 1, "stepSizes": [4, 2], "nTrials": 3}},)");
  ASSERT_EQ(testing::run_cli("export-web " + manifest.string() + " -o " + (dir / "web").string())
                .exit_code,
            0);
  const fs::path db = dir / "study.sqlite";
  const auto links = testing::make_links(dir / "web", db, 1);
  const fs::path page_csv = dir / "page.csv";
  {
    testing::ServerProcess server(dir / "web", db);
    const auto run = testing::run_program(
        "bash -c", "'" +
                       testing::node("web/tools/browser-session.mjs \"" + server.url() +
                                         "?link=" + links[0].second + "\" P001 weibull:0.5,3,11 " +
                                         page_csv.string() + " 5",
                                     "STALL=3") +
                       "'");
    ASSERT_EQ(run.exit_code, 0) << run.output;
    EXPECT_EQ(testing::plans_held(server), 0) << "the completed session's run is let go";
    EXPECT_EQ(server.stop(), 0);
  }
  const std::string page = testing::read_file(page_csv);
  EXPECT_NE(page.find(",mistimed"), std::string::npos);
  ASSERT_EQ(testing::run_cli("serve --data " + db.string() + " --export " + (dir / "out").string())
                .exit_code,
            0);
  EXPECT_EQ(testing::read_file(dir / "out/P001_s01.forced-choice.csv"), page);

  testing::ServerProcess restarted(dir / "web", db);
  httplib::Client client("127.0.0.1", restarted.port());
  const auto status = client.Get("/admin/status.json?token=" + restarted.admin_token());
  ASSERT_TRUE(status);
  EXPECT_EQ(nlohmann::json::parse(status->body)["states"]["completed"], 1) << status->body;
  const CsvTable table = parse_csv(page, "page.csv");
  const std::string header = csv_line(table.rows.front()), last = csv_line(table.rows.back());
  const long rows = long(table.rows.size()) - 1;
  const StudyFolder folder = open_study_folder(dir / "web");
  const std::string key = page_store_key(folder, "P001", 1);
  const httplib::Headers headers = {
      {"Authorization", "Bearer " + testing::read_file(page_csv.string() + ".token")},
      {"Idempotency-Key", key + ":" + std::to_string(rows - 1)}};
  const auto repeat = client.Post("/api/rows", headers, header + last, "text/csv");
  ASSERT_TRUE(repeat);
  EXPECT_EQ(repeat->status, 200) << repeat->body;
  httplib::Headers after = headers;
  after.find("Idempotency-Key")->second = key + ":" + std::to_string(rows);
  const auto extra = client.Post("/api/rows", after, header + last, "text/csv");
  ASSERT_TRUE(extra);
  EXPECT_EQ(extra->status, 422) << extra->body;
  EXPECT_NE(extra->body.find("after the session's last"), std::string::npos) << extra->body;
  EXPECT_EQ(testing::plans_held(restarted), 0) << "made again from the rows for each, and let go";
}

}  // namespace
}  // namespace countershade::serve
