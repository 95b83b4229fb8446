// `countershade serve` end to end: three participants in headless Chromium on the real page, each
// by their link, one reloaded twice on the way. The export holds the rows that `adjust` writes for
// the same subjects and observers, apart from the clock's and the browser's columns, and
// `analyze` gives the same results.json.

#include <gtest/gtest.h>

#include "../web/browser_sessions.h"
#include "served_study.h"

namespace countershade::serve {
namespace {

namespace fs = std::filesystem;

TEST(ServeBrowser, LinkedParticipantsGiveTheAppsRowsThroughTheServer) {
  testing::TempDir dir;
  const fs::path web = testing::exported_study(dir);
  const fs::path manifest = dir / "set/manifest.json";
  const fs::path db = dir / "study.sqlite";
  const auto links = testing::make_links(web, db, 3);
  testing::ServerProcess server(web, db);
  fs::create_directories(dir / "browser");
  std::string app_csvs, export_csvs;
  for (int p = 0; p < 3; ++p) {
    const auto& [subject, link] = links[size_t(p)];
    const std::string seed = std::to_string(p + 1);
    testing::browser_session(server.url() + "?link=" + link, dir / "browser", subject, seed,
                             p == 1 ? "4 9" : "");
    testing::app_session(manifest, dir / "app", subject, seed);
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
  ASSERT_EQ(testing::run_cli("analyze" + export_csvs + " -o " + (dir / "served-report").string() +
                             " --no-figures")
                .exit_code,
            0);
  EXPECT_EQ(testing::read_file(dir / "app-report/results.json"),
            testing::read_file(dir / "served-report/results.json"));
}

}  // namespace
}  // namespace countershade::serve
