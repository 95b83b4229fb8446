// `countershade serve` against strangers: forged and borrowed tokens, a replayed link, oversized,
// malformed and unplanned rows, the wrong content type, a flood, and paths out of the study's
// folder. Each is refused with its status and a line in the log, and the database keeps only the
// one row sent rightly.

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include "serve/sqlite.h"
#include "served_study.h"

namespace countershade::serve {
namespace {

namespace fs = std::filesystem;
using testing::ServerProcess;

// The status and body of a request sent byte for byte as given (no client normalises the path).
std::pair<int, std::string> raw_request(int port, const std::string& request) {
  const int s = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(uint16_t(port));
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(s, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) return {-1, ""};
  ::send(s, request.data(), request.size(), 0);
  std::string response;
  char buffer[4096];
  for (ssize_t n; (n = ::recv(s, buffer, sizeof buffer, 0)) > 0;)
    response.append(buffer, size_t(n));
  ::close(s);
  const int status = response.size() > 12 ? std::stoi(response.substr(9, 3)) : -1;
  return {status, response};
}

int64_t rows_in(const fs::path& db) {
  Connection connection(db, true);
  Statement count(connection.get(), "SELECT count(*) FROM rows");
  return count.step() ? count.integer(0) : -1;
}

struct Stranger {
  testing::TempDir dir;
  StudyFolder folder;
  fs::path db = dir / "study.sqlite";
  std::vector<std::pair<std::string, std::string>> links;
  std::mt19937 random{69};
  std::string token_a = testing::browser_token(random), token_b = testing::browser_token(random);

  Stranger()
      : folder(open_study_folder(testing::exported_study(dir))),
        links(testing::make_links(folder.root, db, 3)) {}

  // A POST of a row with a token, a key and a content type; the status.
  int post(httplib::Client& client, const std::string& token, const std::string& key,
           const std::string& body, const char* type = "text/csv") {
    httplib::Headers headers = {{"Authorization", "Bearer " + token}};
    if (!key.empty()) headers.emplace("Idempotency-Key", key);
    const auto result = client.Post("/api/rows", headers, body, type);
    return result ? result->status : -1;
  }
  int claim(httplib::Client& client, const std::string& token, const std::string& link) {
    const auto result = client.Post("/api/claim", {{"Authorization", "Bearer " + token}},
                                    "{\"link\":\"" + link + "\"}", "application/json");
    return result ? result->status : -1;
  }
};

TEST(ServeStrangers, EveryStrangerIsRefusedAndNothingIsWritten) {
  Stranger t;
  // A symbolic link inside the study's folder, to a file and to a folder outside it.
  testing::write_file(t.dir / "secret.txt", "not for participants");
  fs::create_symlink(t.dir / "secret.txt", t.folder.root / "secret.txt");
  fs::create_symlink(t.dir.path(), t.folder.root / "outside");
  ServerProcess server(t.folder.root, t.db, {"--rate", "5", "--burst", "10"});
  httplib::Client client("127.0.0.1", server.port());
  const auto& [subject_a, link_a] = t.links[0];
  const auto& [subject_b, link_b] = t.links[1];
  ASSERT_EQ(t.claim(client, t.token_a, link_a), 200);
  ASSERT_EQ(t.claim(client, t.token_b, link_b), 200);
  const std::vector<std::string> lines = testing::planned_lines(t.folder, subject_a, t.random);
  const std::string header = csv_line(t.folder.columns);
  const std::string key_a0 = testing::row_key(t.folder, subject_a, 0);
  ASSERT_EQ(t.post(client, t.token_a, key_a0, header + lines[0]), 201);  // the one right row

  EXPECT_EQ(t.claim(client, testing::browser_token(t.random), link_a), 410) << "replayed link";
  EXPECT_EQ(t.claim(client, t.token_a, std::string(32, 'a')), 403) << "forged link";
  EXPECT_EQ(t.post(client, testing::browser_token(t.random),
                   testing::row_key(t.folder, subject_a, 1), header + lines[1]),
            403)
      << "forged token";
  EXPECT_EQ(t.post(client, t.token_b, testing::row_key(t.folder, subject_a, 1), header + lines[1]),
            403)
      << "another participant's token on A's key";
  EXPECT_EQ(t.post(client, t.token_b, testing::row_key(t.folder, subject_b, 0), header + lines[1]),
            403)
      << "A's row under B's token and key";
  EXPECT_EQ(t.post(client, t.token_a, key_a0, header + lines[1]), 409) << "another row, used key";
  EXPECT_EQ(t.post(client, t.token_a, testing::row_key(t.folder, subject_a, 5), header + lines[5]),
            409)
      << "a row past the next";
  std::vector<std::string> fields = parse_csv(lines[1], "row").rows[0];
  fields[3] = "medium";  // the question column
  const std::string unplanned = csv_line(fields);
  EXPECT_EQ(t.post(client, t.token_a, testing::row_key(t.folder, subject_a, 1), header + unplanned),
            422)
      << "a question the plan does not have";
  EXPECT_EQ(t.post(client, t.token_a, testing::row_key(t.folder, subject_a, 1),
                   header + "P001,\"unterminated\n"),
            400)
      << "malformed CSV";
  EXPECT_EQ(t.post(client, t.token_a, testing::row_key(t.folder, subject_a, 1), header + lines[1],
                   "application/json"),
            415)
      << "wrong content type";
  EXPECT_EQ(t.post(client, t.token_a, testing::row_key(t.folder, subject_a, 1),
                   header + lines[1] + std::string(20000, ' ')),
            413)
      << "oversized body";

  for (const char* path :
       {"/../secret.txt", "/%2e%2e/secret.txt", "/images/../../secret.txt", "/%2E%2E%2Fsecret.txt",
        "//etc/passwd", "http://x/etc/passwd", "/etc/passwd", "/secret.txt", "/outside/secret.txt",
        "/images/", "/.", "/study.js%00.png"}) {
    const auto [status, body] =
        raw_request(server.port(), std::string("GET ") + path +
                                       " HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
    EXPECT_TRUE(status == 404 || status == 400) << path << ": " << status;
    EXPECT_EQ(body.find("not for participants"), std::string::npos) << path;
    EXPECT_EQ(body.find("root:"), std::string::npos) << path;
  }
  const auto [index_status, index] =
      raw_request(server.port(), "GET / HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
  EXPECT_EQ(index_status, 200);
  EXPECT_NE(index.find("Content-Security-Policy: default-src 'self'"), std::string::npos);
  // No eval: the page's scripts and the engine's bindings run without building code.
  EXPECT_NE(index.find("script-src 'self' 'wasm-unsafe-eval';"), std::string::npos);
  EXPECT_EQ(index.find("'unsafe-eval'"), std::string::npos);

  // A flood of repeats: the rate limit answers 429 to some, and a repeat writes nothing anyway.
  int limited = 0;
  for (int i = 0; i < 40; ++i)
    limited += t.post(client, t.token_a, key_a0, header + lines[0]) == 429;
  EXPECT_GT(limited, 0);

  EXPECT_EQ(rows_in(t.db), 1);
  const auto status = client.Get("/admin/status.json?token=" + server.admin_token());
  ASSERT_TRUE(status && status->status == 200);
  const auto refused = nlohmann::json::parse(status->body)["refused"];
  for (const char* kind :
       {"replayed link", "forged link", "forged token", "another session's key",
        "another participant's row", "conflicting row", "row out of order", "not in the plan",
        "malformed row", "wrong content type", "oversized body", "not found", "too many requests"})
    EXPECT_GE(refused.value(kind, 0), 1) << kind << " in " << refused.dump();
  EXPECT_EQ(client.Get("/admin/status.json?token=" + std::string(32, '0'))->status, 403);
  EXPECT_EQ(server.stop(), 0);
  const std::string log = server.log();
  EXPECT_NE(log.find("refused 410 (replayed link)"), std::string::npos) << log;
}

// In open mode a participant names an id: the browser that claimed it first keeps it, another
// browser is refused, a malformed id is refused; without --open an id alone opens nothing.
TEST(ServeStrangers, AnOpenStudyGivesEachIdToOneBrowser) {
  Stranger t;
  const auto claim = [&](int port, const std::string& token, const std::string& body) {
    const auto result =
        httplib::Client("127.0.0.1", port)
            .Post("/api/claim", {{"Authorization", "Bearer " + token}}, body, "application/json");
    return result ? result->status : -1;
  };
  {
    ServerProcess linked(t.folder.root, t.db);
    EXPECT_EQ(claim(linked.port(), t.token_a, R"({"subject": "Q1", "session": 1})"), 403);
  }
  ServerProcess open(t.folder.root, t.db, {"--open"});
  EXPECT_EQ(claim(open.port(), t.token_a, R"({"subject": "Q1", "session": 1})"), 200);
  EXPECT_EQ(claim(open.port(), t.token_a, R"({"subject": "Q1", "session": 1})"), 200);
  EXPECT_EQ(claim(open.port(), t.token_b, R"({"subject": "Q1", "session": 1})"), 409);
  EXPECT_EQ(claim(open.port(), t.token_b, R"({"subject": "../Q1", "session": 1})"), 400);
  EXPECT_EQ(claim(open.port(), t.token_b, R"({"subject": "Q2", "session": 100})"), 400);
  EXPECT_EQ(claim(open.port(), "not-a-token", R"({"subject": "Q2", "session": 1})"), 401);
  EXPECT_EQ(claim(open.port(), t.token_b, "[1, 2"), 400);
  EXPECT_EQ(claim(open.port(), t.token_b, R"({"subject": 5, "session": "1"})"), 400);
  EXPECT_EQ(claim(open.port(), t.token_b, R"({"subject": "Q2", "session": 1e12})"), 400);
  EXPECT_EQ(claim(open.port(), t.token_b, R"({"subject": "Q2", "session": 4294967297})"), 400);
  EXPECT_EQ(claim(open.port(), t.token_b, R"({"subject": "Q2", "session": 2})"), 200);
  const auto status = httplib::Client("127.0.0.1", open.port())
                          .Get("/admin/status.json?token=" + open.admin_token());
  ASSERT_TRUE(status);
  EXPECT_EQ(nlohmann::json::parse(status->body)["sessions"].size(), 2u) << status->body;
}

// A database holds one study: another export (another set) is refused, in one line, and the
// database is left as it was. One server holds a database, and a port.
TEST(ServeStrangers, ADatabaseServesOneStudyOnly) {
  Stranger t;
  testing::TempDir other;
  const fs::path other_web =
      testing::exported_study(other, R"({"repetitions": 2})");  // the same set: another plan
  const std::string before = testing::read_file(t.db);
  testing::write_file(other_web / "study.js",
                      std::regex_replace(testing::read_file(other_web / "study.js"),
                                         std::regex(t.folder.set_sha256), std::string(64, 'e')));
  const auto run =
      testing::run_cli("serve " + other_web.string() + " --data " + t.db.string() + " --open");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.output.find("holds the answers of another study"), std::string::npos) << run.output;
  EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1);
  EXPECT_EQ(testing::read_file(t.db), before);

  // Nor do two servers share a database or a port.
  ServerProcess first(t.folder.root, t.db, {"--open"});
  const auto same_db = testing::run_cli("serve " + t.folder.root.string() + " --data " +
                                        t.db.string() + " --open --port 0");
  EXPECT_EQ(same_db.exit_code, 2);
  EXPECT_NE(same_db.output.find("another countershade serve holds it"), std::string::npos);
  const auto same_port = testing::run_cli("serve " + t.folder.root.string() + " --data " +
                                          (t.dir / "other.sqlite").string() + " --open --port " +
                                          std::to_string(first.port()));
  EXPECT_EQ(same_port.exit_code, 2);
  EXPECT_NE(same_port.output.find("cannot listen"), std::string::npos) << same_port.output;
  // Links, though, can be added while it runs, and claimed at once.
  const auto more = testing::make_links(t.folder.root, t.db, 2);
  std::mt19937 random(7);
  httplib::Client client("127.0.0.1", first.port());
  EXPECT_EQ(t.claim(client, testing::browser_token(random), more.back().second), 200);
  EXPECT_EQ(more.back().first, "P005");
}

}  // namespace
}  // namespace countershade::serve
