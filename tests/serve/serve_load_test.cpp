// `countershade serve` under load and faults: 200 participants send full sessions at once while
// the server is killed (SIGKILL) five times and restarted. Every row acknowledged before a kill is
// in the database after it; at the end every row is there exactly once, the database is intact,
// and the export equals what each participant sent.

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <atomic>
#include <mutex>
#include <set>

#include "serve/sqlite.h"
#include "served_study.h"

namespace countershade::serve {
namespace {

namespace fs = std::filesystem;
using testing::ServerProcess;

constexpr int kParticipants = 200;

struct Participant {
  std::string subject, link, token;
  std::vector<std::string> lines;
};

// What the participants have been told is stored: (subject, row index).
class Acknowledged {
 public:
  void add(const std::string& subject, long index) {
    std::lock_guard lock(mutex_);
    rows_.emplace(subject, index);
  }
  std::set<std::pair<std::string, long>> snapshot() const {
    std::lock_guard lock(mutex_);
    return rows_;
  }
  size_t size() const { return snapshot().size(); }

 private:
  mutable std::mutex mutex_;
  std::set<std::pair<std::string, long>> rows_;
};

// One participant's whole session: the claim, then each row after a random pause, each sent until
// acknowledged. The port stays the same across restarts.
void run_participant(const Participant& p, const StudyFolder& folder, int port, unsigned seed,
                     Acknowledged& acknowledged, std::atomic<int>& refused) {
  std::mt19937 random(seed);
  httplib::Client client("127.0.0.1", port);
  client.set_connection_timeout(2);
  client.set_read_timeout(30);
  const httplib::Headers auth = {{"Authorization", "Bearer " + p.token}};
  if (testing::post_until_ok(client, "/api/claim", auth, "{\"link\":\"" + p.link + "\"}",
                             "application/json") /
          100 !=
      2)
    ++refused;
  for (size_t i = 0; i < p.lines.size(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(random() % 40));
    httplib::Headers headers = auth;
    headers.emplace("Idempotency-Key", testing::row_key(folder, p.subject, long(i)));
    const int status = testing::post_until_ok(client, "/api/rows", headers,
                                              csv_line(folder.columns) + p.lines[i], "text/csv");
    if (status / 100 == 2)
      acknowledged.add(p.subject, long(i));
    else
      ++refused;
  }
}

// The rows the database holds, as (subject, index) → line.
std::map<std::pair<std::string, long>, std::string> stored_rows(const fs::path& db) {
  Connection connection(db, false);
  Statement s(connection.get(),
              "SELECT subject, row_index, line FROM rows JOIN sessions ON id = session_id");
  std::map<std::pair<std::string, long>, std::string> rows;
  while (s.step()) rows[{s.text(0), long(s.integer(1))}] = s.text(2);
  return rows;
}

std::vector<Participant> participants(const StudyFolder& folder, const fs::path& db) {
  std::mt19937 random(68);
  std::vector<Participant> all;
  for (const auto& [subject, link] : testing::make_links(folder.root, db, kParticipants))
    all.push_back({subject, link, testing::browser_token(random),
                   testing::planned_lines(folder, subject, random)});
  return all;
}

TEST(ServeLoad, EveryAcknowledgedRowSurvivesFiveKillsAndIsKeptOnce) {
  testing::TempDir dir;
  const StudyFolder folder =
      open_study_folder(testing::exported_study(dir, R"({"repetitions": 5})"));
  const fs::path db = dir / "study.sqlite";
  const std::vector<Participant> all = participants(folder, db);
  size_t total = 0;
  for (const Participant& p : all) total += p.lines.size();
  ASSERT_GE(all.front().lines.size(), 60u);
  auto server = std::make_unique<ServerProcess>(folder.root, db);
  const int port = server->port();
  Acknowledged acknowledged;
  std::atomic<int> refused = 0;
  std::vector<std::thread> threads;
  for (size_t i = 0; i < all.size(); ++i)
    threads.emplace_back(run_participant, std::cref(all[i]), std::cref(folder), port,
                         unsigned(i + 1), std::ref(acknowledged), std::ref(refused));
  for (int kill = 1; kill <= 5; ++kill) {
    while (acknowledged.size() < total * size_t(kill) / 6)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const auto before = acknowledged.snapshot();
    server->kill_hard();
    const auto rows = stored_rows(db);
    size_t missing = 0;
    for (const auto& row : before) missing += rows.count(row) == 0;
    EXPECT_EQ(missing, 0u) << "after kill " << kill << " of " << before.size() << " acknowledged";
    server = std::make_unique<ServerProcess>(folder.root, db, std::vector<std::string>{}, port);
  }
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(refused, 0);
  EXPECT_EQ(acknowledged.size(), total);
  EXPECT_EQ(server->stop(), 0) << server->log();

  const auto rows = stored_rows(db);
  EXPECT_EQ(rows.size(), total);
  for (const Participant& p : all)
    for (size_t i = 0; i < p.lines.size(); ++i)
      EXPECT_EQ(rows.count({p.subject, long(i)}) ? rows.at({p.subject, long(i)}) : "missing",
                p.lines[i]);
  Connection connection(db, true);
  Statement integrity(connection.get(), "PRAGMA integrity_check");
  ASSERT_TRUE(integrity.step());
  EXPECT_EQ(integrity.text(0), "ok");

  ASSERT_EQ(testing::run_cli("serve --data " + db.string() + " --export " + (dir / "out").string())
                .exit_code,
            0);
  for (const Participant& p : all) {
    std::string expected = csv_line(folder.columns);
    for (const std::string& line : p.lines) expected += line;
    EXPECT_EQ(testing::read_file(dir / "out" / (p.subject + "_s01.csv")), expected) << p.subject;
  }
}

// A session idle for --abandoned-after (here 1.2 s) is let go when another session posts, and
// made again from its stored rows when it posts again: its next row is taken and a row out of its
// plan still refused.
TEST(ServeLoad, AnIdleSessionsPlanIsLetGoAndMadeAgainFromItsRows) {
  testing::TempDir dir;
  const StudyFolder folder = open_study_folder(testing::exported_study(dir));
  const fs::path db = dir / "study.sqlite";
  std::mt19937 random(12);
  std::vector<Participant> two;
  for (const auto& [subject, link] : testing::make_links(folder.root, db, 2))
    two.push_back({subject, link, testing::browser_token(random),
                   testing::planned_lines(folder, subject, random)});
  ServerProcess server(folder.root, db, {"--abandoned-after", "0.02"});
  httplib::Client client("127.0.0.1", server.port());
  const auto post = [&](const Participant& p, long index, const std::string& line) {
    const httplib::Headers headers = {
        {"Authorization", "Bearer " + p.token},
        {"Idempotency-Key", testing::row_key(folder, p.subject, index)}};
    const auto result =
        client.Post("/api/rows", headers, csv_line(folder.columns) + line, "text/csv");
    return result ? result->status : -1;
  };
  for (const Participant& p : two)
    ASSERT_EQ(client
                  .Post("/api/claim", {{"Authorization", "Bearer " + p.token}},
                        "{\"link\":\"" + p.link + "\"}", "application/json")
                  ->status,
              200);
  const Participant &a = two[0], &b = two[1];
  ASSERT_EQ(post(a, 0, a.lines[0]), 201);
  EXPECT_EQ(testing::plans_held(server), 1);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  ASSERT_EQ(post(b, 0, b.lines[0]), 201);
  EXPECT_EQ(testing::plans_held(server), 1) << "a's plan, idle for longer, is let go";
  std::vector<std::string> unplanned = parse_csv(a.lines[1], "row").rows.at(0);
  unplanned[size_t(std::find(folder.columns.begin(), folder.columns.end(), "trial") -
                   folder.columns.begin())] = "999";
  EXPECT_EQ(post(a, 1, csv_line(unplanned)), 422) << "a trial out of a's plan made again";
  EXPECT_EQ(post(a, 1, a.lines[1]), 201);
  EXPECT_EQ(testing::plans_held(server), 2);
  EXPECT_EQ(server.stop(), 0);
}

}  // namespace
}  // namespace countershade::serve
