#pragma once
// What the serve tests share: a tiny set exported for the web, a `countershade serve` process
// hosting it (started, killed and restarted like a real one), and participants that claim a link
// and send their rows as the page does.

#include <httplib.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "../adjust/tiny_set.h"
#include "../adjust/x_display.h"
#include "core/time.h"
#include "formats/responses.h"
#include "serve/study_folder.h"
#include "test_util.h"
#include "web_engine/page_study.h"

namespace countershade::testing {

// A tiny set (adjust settings `adjust`) exported for the web into dir/web.
inline std::filesystem::path exported_study(const TempDir& dir, const std::string& adjust = "") {
  const auto manifest = make_tiny_set(dir, adjust);
  const auto run = run_cli("export-web " + manifest.string() + " -o " + (dir / "web").string());
  if (run.exit_code != 0) throw std::runtime_error("export-web failed: " + run.output);
  return dir / "web";
}

// `countershade serve WEB --data DB ARGS…` as a child process, on `port` (0: any free one).
class ServerProcess {
 public:
  ServerProcess(const std::filesystem::path& web, const std::filesystem::path& db,
                const std::vector<std::string>& args = {}, int port = 0)
      : log_(db.string() + ".log." + std::to_string(++starts_)) {
    std::vector<std::string> argv = {COUNTERSHADE_BINARY, "serve",  web.string(),        "--data",
                                     db.string(),         "--port", std::to_string(port)};
    argv.insert(argv.end(), args.begin(), args.end());
    child_ = std::make_unique<Child>(argv, "", log_);
    // Its first line is the URL; a bound only catches a server that never starts.
    for (int i = 0; i < 12000 && url_.empty() && child_->running(); ++i) {
      const std::string log = read_file(log_);
      if (log.rfind("http://", 0) == 0) url_ = log.substr(0, log.find('\n'));
      if (url_.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (url_.empty()) throw std::runtime_error("serve did not start: " + read_file(log_));
    port_ = std::stoi(url_.substr(url_.rfind(':') + 1));
  }
  const std::string& url() const { return url_; }
  int port() const { return port_; }
  std::string log() const { return read_file(log_); }
  // The admin token the server printed.
  std::string admin_token() const {
    const std::string log = read_file(log_);
    const size_t at = log.find("token=");
    return at == std::string::npos ? "" : log.substr(at + 6, 32);
  }
  void kill_hard() { child_->kill_hard(); }
  // SIGTERM; the exit status.
  int stop() {
    child_->send(SIGTERM);
    return child_->wait(120);
  }

 private:
  static inline int starts_ = 0;
  std::string log_;
  std::unique_ptr<Child> child_;
  std::string url_;
  int port_ = 0;
};

// The links `serve --links` wrote: (subject, link token) each.
inline std::vector<std::pair<std::string, std::string>> make_links(const std::filesystem::path& web,
                                                                   const std::filesystem::path& db,
                                                                   int count) {
  static int calls = 0;  // each call its own file: links are never overwritten
  const auto csv = db.string() + ".links-" + std::to_string(++calls) + ".csv";
  const auto run = run_cli("serve " + web.string() + " --data " + db.string() + " --links " +
                           std::to_string(count) + " --links-csv " + csv);
  if (run.exit_code != 0) throw std::runtime_error("serve --links failed: " + run.output);
  std::vector<std::pair<std::string, std::string>> links;
  const CsvTable table = parse_csv(read_file(csv), csv);
  for (size_t r = 1; r < table.rows.size(); ++r)
    links.emplace_back(table.rows[r][0],
                       table.rows[r][2].substr(table.rows[r][2].find("link=") + 5));
  return links;
}

// Every row a complete session of `subject` sends, as CSV lines in the page's order: each
// question of each planned trial, with λ indices drawn from `random`, and a user agent that needs
// quoting.
inline std::vector<std::string> planned_lines(const serve::StudyFolder& folder,
                                              const std::string& subject, std::mt19937& random) {
  std::vector<std::string> lines;
  const nlohmann::json& page = folder.page;
  for (const adjust::Trial& t : web_engine::page_plan(page, subject, 1)) {
    if (t.practice) continue;
    const nlohmann::json& c = page["conditions"][size_t(t.condition)];
    for (int q = 0; q < kQuestionCount; ++q) {
      const size_t index = std::uniform_int_distribution<size_t>(0, c["grid"].size() - 1)(random);
      const std::map<std::string, std::string> value = {
          {"subject", subject},
          {"scene", c["scene"]},
          {"sigma", c["sigma"]},
          {"question", kQuestionNames[q]},
          {"lambda", c["grid"][index]},
          {"method", c["method"]},
          {"lambda_step", page["lambda_step"]},
          {"lambda_index", std::to_string(index)},
          {"lambda_max", c["lambda_max"]},
          {"start_index", std::to_string(t.start_index[q])},
          {"repetition", std::to_string(t.repetition)},
          {"session", "1"},
          {"trial", std::to_string(t.number)},
          {"side", procedures::side_name(t.side)},
          {"n_keypresses", "3"},
          {"rt_ms", "812.5"},
          {"revision", "0"},
          {"timestamp_utc", utc_timestamp()},
          {"stimulus_set", folder.set_sha256},
          {"app_version", folder.app_version},
          {"sequence", ""},
          {"device_pixel_ratio", "1"},
          {"window_width", "900"},
          {"window_height", "600"},
          {"refresh_hz", "60"},
          {"user_agent", "Mozilla/5.0 (X11, \"load test\")"},
          {"css_px_per_mm", ""},
          {"viewing_distance_mm", ""},
          {"stimulus_bits", "8"},
          {"output_path", "8-bit"}};
      std::vector<std::string> fields;
      for (const std::string& column : folder.columns) fields.push_back(value.at(column));
      lines.push_back(csv_line(fields));
    }
  }
  return lines;
}

// The page's Idempotency-Key for row `index` of a subject's first session.
inline std::string row_key(const serve::StudyFolder& folder, const std::string& subject,
                           long index) {
  std::string key = serve::page_store_key(folder, subject, 1);
  for (size_t at; (at = key.find(':')) != std::string::npos;) key.replace(at, 1, "%3A");
  return key + ":" + std::to_string(index);
}

// A browser's token (any 32 hex digits).
inline std::string browser_token(std::mt19937& random) {
  std::string token;
  for (int i = 0; i < 32; ++i) token += "0123456789abcdef"[random() % 16];
  return token;
}

// POSTs until the server answers 2xx, waiting after each failure as the page does (100 ms,
// doubling up to 5 s); returns that status, or a refusal (4xx other than 429), which no retry
// would change. `attempts` counts every try.
inline int post_until_ok(httplib::Client& client, const std::string& path,
                         const httplib::Headers& headers, const std::string& body, const char* type,
                         int* attempts = nullptr) {
  for (int wait_ms = 100;; wait_ms = std::min(5000, 2 * wait_ms)) {
    if (attempts) ++*attempts;
    const auto result = client.Post(path, headers, body, type);
    if (result &&
        (result->status / 100 == 2 || (result->status / 100 == 4 && result->status != 429)))
      return result->status;
    std::this_thread::sleep_for(std::chrono::milliseconds(wait_ms));
  }
}

// The session plans a server holds (/admin/status.json's plans_held); -1 if it does not answer.
inline int plans_held(ServerProcess& server) {
  const auto status = httplib::Client("127.0.0.1", server.port())
                          .Get("/admin/status.json?token=" + server.admin_token());
  return status ? nlohmann::json::parse(status->body).value("plans_held", -1) : -1;
}

}  // namespace countershade::testing
