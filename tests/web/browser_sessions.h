#pragma once
// What the browser tests share: Node.js tools run from the source tree with this build's
// WebAssembly engine, a session of the app and one of the page with the same observer, and the
// rows of a responses CSV that both must have alike.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "../adjust/x_display.h"
#include "formats/responses.h"
#include "test_util.h"

namespace countershade::testing {

namespace fs = std::filesystem;

// `countershade export-web MANIFEST -o WEB OPTIONS`, which must succeed (a fatal failure if not:
// call it inside ASSERT_NO_FATAL_FAILURE).
inline void export_web(const fs::path& manifest, const fs::path& web,
                       const std::string& options = "") {
  const auto run = run_cli("export-web " + manifest.string() + " -o " + web.string() +
                           (options.empty() ? "" : " " + options));
  ASSERT_EQ(run.exit_code, 0) << run.output;
}

// A Node.js command run from the source tree (where node_modules/ is), with this build's
// WebAssembly engine; `environment`: VAR=value …
inline std::string node(const std::string& arguments, const std::string& environment = "") {
  return "cd " + source_dir().string() +
         " && COUNTERSHADE_WEB_ENGINE=" COUNTERSHADE_WEB_ENGINE " " + environment + " node " +
         arguments;
}

// The rows of a responses CSV without the columns that depend on the clock or the browser.
inline std::vector<std::vector<std::string>> comparable_rows(const fs::path& csv) {
  const CsvTable table = parse_csv(read_file(csv), csv.string());
  std::vector<std::string> keep = response_columns();
  std::erase_if(keep, [](const std::string& c) { return c == "rt_ms" || c == "timestamp_utc"; });
  std::vector<std::vector<std::string>> rows;
  for (const auto& row : table.rows) {
    std::vector<std::string> kept;
    for (const std::string& c : keep) {
      const auto at =
          std::find(table.rows[0].begin(), table.rows[0].end(), c) - table.rows[0].begin();
      kept.push_back(size_t(at) < row.size() ? row[size_t(at)] : "?");
    }
    rows.push_back(kept);
  }
  return rows;
}

// The app's session of the observer `spec` (a number: simulated:NUMBER), on the frame clock, into
// `sessions`.
inline void app_session(const fs::path& manifest, const fs::path& sessions,
                        const std::string& subject, const std::string& spec) {
  XvfbServer x;
  const std::string observer = spec.find(':') == std::string::npos ? "simulated:" + spec : spec;
  Child app({COUNTERSHADE_BINARY, "adjust", manifest.string(), "--subject", subject, "--sessions",
             sessions.string(), "--observer", observer, "--frame-clock"},
            x.display(), (sessions.parent_path() / "app-log.txt").string());
  ASSERT_EQ(app.wait(300), 0) << read_file(sessions.parent_path() / "app-log.txt");
}

// The browser's session of the same observer (reloading after the given numbers of answers);
// returns the CSV the page offers; the rows its server accepted are in CSV.posted.
inline fs::path browser_session(const fs::path& study, const fs::path& out,
                                const std::string& subject, const std::string& spec,
                                const std::string& reloads = "", int refuse = 0) {
  const fs::path csv = out / (subject + "_s01.csv");
  const auto run =
      run_program("bash -c", "'" +
                                 node("web/tools/browser-session.mjs " + study.string() + " " +
                                          subject + " " + spec + " " + csv.string() + " " + reloads,
                                      "REFUSE=" + std::to_string(refuse)) +
                                 "'");
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return csv;
}

}  // namespace countershade::testing
