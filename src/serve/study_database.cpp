#include "serve/study_database.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdio>

#include "core/error.h"
#include "core/time.h"
#include "formats/responses.h"
#include "serve/refusal.h"
#include "serve/tokens.h"

namespace countershade::serve {
namespace {

constexpr const char* kFormat = "countershade-serve 1";
// The most writes one transaction commits: enough to carry 2,000 rows/s on one fsync per batch.
constexpr size_t kLargestBatch = 1024;

constexpr const char* kSchema = R"sql(
CREATE TABLE IF NOT EXISTS study(key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE IF NOT EXISTS links(token_hash TEXT PRIMARY KEY, subject TEXT NOT NULL,
  session INTEGER NOT NULL, claimed_by TEXT, UNIQUE(subject, session));
CREATE TABLE IF NOT EXISTS sessions(id INTEGER PRIMARY KEY, token_hash TEXT NOT NULL UNIQUE,
  subject TEXT NOT NULL, session INTEGER NOT NULL, started TEXT NOT NULL,
  last_activity TEXT NOT NULL, completed INTEGER NOT NULL DEFAULT 0, UNIQUE(subject, session));
CREATE TABLE IF NOT EXISTS rows(session_id INTEGER NOT NULL REFERENCES sessions(id),
  row_index INTEGER NOT NULL, line TEXT NOT NULL, answer TEXT NOT NULL, received TEXT NOT NULL,
  PRIMARY KEY(session_id, row_index)) WITHOUT ROWID;
)sql";

std::string study_value(sqlite3* db, const char* key) {
  Statement s(db, "SELECT value FROM study WHERE key = ?");
  s.bind(1, std::string(key));
  return s.step() ? s.text(0) : "";
}

std::optional<int64_t> session_id_of(sqlite3* db, const std::string& subject, int session) {
  Statement s(db, "SELECT id FROM sessions WHERE subject = ? AND session = ?");
  s.bind(1, subject).bind(2, int64_t(session));
  if (s.step()) return s.integer(0);
  return std::nullopt;
}

bool token_taken(sqlite3* db, const std::string& hash) {
  Statement s(db, "SELECT 1 FROM sessions WHERE token_hash = ?");
  s.bind(1, hash);
  return s.step();
}

[[noreturn]] void refuse_reused_token() {
  throw Refusal(409, "token reused", "claim: the token already holds another session");
}

[[noreturn]] void refuse_taken(const std::string& subject, int session) {
  throw Refusal(
      409, "session taken",
      "claim: " + subject + " session " + std::to_string(session) + " belongs to another browser");
}

// The file, opened and locked for this process alone. flock() locks are apart from the POSIX
// locks SQLite takes, and the descriptor stays open until the connection is closed, so SQLite's
// own locks are never released by closing it.
int lock_database(const std::filesystem::path& file) {
  const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw_input_error(file.string(), "cannot be opened for writing");
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd);
    throw_input_error(file.string(), "another countershade serve holds it");
  }
  return fd;
}

}  // namespace

StudyDatabase::StudyDatabase(const std::filesystem::path& file, const StudyFolder& folder,
                             Holder holder)
    : file_(file),
      lock_(holder == Holder::server ? lock_database(file) : -1),
      connection_(file, false) {
  try {
    connection_.execute("PRAGMA journal_mode=WAL; PRAGMA synchronous=FULL;");
    connection_.execute(kSchema);
    create_or_check(folder);
    load_sessions();
  } catch (const SqliteError& e) {
    throw_input_error(file.string(), std::string("not a study database (") + e.what() + ")");
  }
  writer_ = std::thread([this] { writer_loop(); });
}

StudyDatabase::~StudyDatabase() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  queued_.notify_all();
  writer_.join();
  connection_.close();
  if (lock_ >= 0) ::close(lock_);
}

void StudyDatabase::create_or_check(const StudyFolder& folder) {
  sqlite3* db = connection_.get();
  const std::string set = study_value(db, "set_sha256");
  if (set.empty()) {
    Statement insert(db, "INSERT INTO study(key, value) VALUES (?, ?)");
    const std::pair<const char*, std::string> values[] = {
        {"format", kFormat},
        {"set_sha256", folder.set_sha256},
        {"app_version", folder.app_version},
        {"kind", folder.kind == StudyKind::adjustment ? "adjustment" : "forced_choice"},
        {"title", folder.title},
        {"columns", csv_line(folder.columns)},
        {"created", utc_timestamp(false)}};
    connection_.execute("BEGIN IMMEDIATE");
    for (const auto& [key, value] : values) insert.bind(1, std::string(key)).bind(2, value).run();
    connection_.execute("COMMIT");
    return;
  }
  if (study_value(db, "format") != kFormat)
    throw_input_error(file_.string(), "was not written by countershade serve");
  if (set != folder.set_sha256 || study_value(db, "app_version") != folder.app_version)
    throw_input_error(file_.string(), "holds the answers of another study (set " +
                                          set.substr(0, 12) + ", version " +
                                          study_value(db, "app_version") +
                                          "): give this study a database of its own");
}

void StudyDatabase::load_sessions() {
  Statement s(connection_.get(), "SELECT id, token_hash, subject, session FROM sessions");
  while (s.step()) sessions_[s.text(1)] = {s.integer(0), s.text(2), int(s.integer(3))};
  Statement links(connection_.get(), "SELECT count(*) FROM links");
  has_links_ = links.step() && links.integer(0) > 0;
}

bool StudyDatabase::has_links() const {
  std::lock_guard lock(mutex_);
  return has_links_;
}

std::optional<SessionRecord> StudyDatabase::session_of(const std::string& hash) const {
  std::lock_guard lock(mutex_);
  const auto found = sessions_.find(hash);
  if (found == sessions_.end()) return std::nullopt;
  return found->second;
}

void StudyDatabase::run(Job job) {
  std::future<void> done = job.done.get_future();
  {
    std::lock_guard lock(mutex_);
    queue_.push_back(std::move(job));
  }
  queued_.notify_one();
  done.get();
}

void StudyDatabase::writer_loop() {
  for (;;) {
    std::vector<Job> batch;
    {
      std::unique_lock lock(mutex_);
      queued_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
      if (queue_.empty()) return;
      while (!queue_.empty() && batch.size() < kLargestBatch) {
        batch.push_back(std::move(queue_.front()));
        queue_.pop_front();
      }
    }
    commit_batch(batch);
  }
}

// One transaction for the batch. A job refused leaves nothing behind (it refuses before writing);
// a storage failure rolls the whole batch back and every job in it is answered 503, so its client
// sends again.
void StudyDatabase::commit_batch(std::vector<Job>& batch) {
  std::vector<std::exception_ptr> outcome(batch.size());
  try {
    connection_.execute("BEGIN IMMEDIATE");
    for (size_t j = 0; j < batch.size(); ++j) try {
        batch[j].work(connection_.get());
      } catch (const Refusal&) {
        outcome[j] = std::current_exception();
      }
    connection_.execute("COMMIT");
  } catch (const SqliteError& e) {
    std::fprintf(stderr, "serve: storage failed, %zu writes not acknowledged: %s\n", batch.size(),
                 e.what());
    sqlite3_exec(connection_.get(), "ROLLBACK", nullptr, nullptr, nullptr);
    for (auto& o : outcome)
      o = std::make_exception_ptr(Refusal(503, "storage failure", "storage failed"));
  }
  std::lock_guard lock(mutex_);
  for (size_t j = 0; j < batch.size(); ++j) {
    if (outcome[j]) {
      batch[j].done.set_exception(outcome[j]);
      continue;
    }
    if (batch[j].after_commit) batch[j].after_commit();
    batch[j].done.set_value();
  }
}

std::vector<NewLink> StudyDatabase::add_links(int count, const std::string& prefix) {
  std::vector<NewLink> links;
  run({[&](sqlite3* db) {
         Statement existing(db, "SELECT count(*) FROM links");
         const int64_t first = existing.step() ? existing.integer(0) + 1 : 1;
         Statement insert(db, "INSERT INTO links(token_hash, subject, session) VALUES (?, ?, 1)");
         for (int64_t n = first; n < first + count; ++n) {
           std::string number = std::to_string(n);
           number.insert(0, number.size() < 3 ? 3 - number.size() : 0, '0');
           NewLink link{prefix + number, 1, random_token()};
           insert.bind(1, token_hash(link.token)).bind(2, link.subject).run();
           links.push_back(std::move(link));
         }
       },
       [&] { has_links_ = has_links_ || count > 0; },
       {}});
  return links;
}

SessionRecord StudyDatabase::insert_session(sqlite3* db, const std::string& subject, int session,
                                            const std::string& hash) {
  Statement insert(db,
                   "INSERT INTO sessions(token_hash, subject, session, started, last_activity) "
                   "VALUES (?, ?, ?, ?, ?)");
  const std::string now = utc_timestamp();
  insert.bind(1, hash).bind(2, subject).bind(3, int64_t(session)).bind(4, now).bind(5, now).run();
  return {sqlite3_last_insert_rowid(db), subject, session};
}

SessionRecord StudyDatabase::claim_link(const std::string& link_hash, const std::string& hash) {
  SessionRecord record;
  run({[&](sqlite3* db) {
         Statement link(db, "SELECT subject, session, claimed_by FROM links WHERE token_hash = ?");
         link.bind(1, link_hash);
         if (!link.step()) throw Refusal(403, "forged link", "claim: no such link");
         const std::string subject = link.text(0), claimed_by = link.text(2);
         const int session = int(link.integer(1));
         if (!claimed_by.empty() && claimed_by != hash)
           throw Refusal(410, "replayed link", "claim: the link was used in another browser");
         if (const auto id = session_id_of(db, subject, session)) {
           if (claimed_by != hash) refuse_taken(subject, session);
           record = {*id, subject, session};
           return;
         }
         if (token_taken(db, hash)) refuse_reused_token();
         record = insert_session(db, subject, session, hash);
         Statement claim(db, "UPDATE links SET claimed_by = ? WHERE token_hash = ?");
         claim.bind(1, hash).bind(2, link_hash).run();
       },
       [&] { sessions_[hash] = record; },
       {}});
  return record;
}

SessionRecord StudyDatabase::open_session(const std::string& subject, int session,
                                          const std::string& hash) {
  SessionRecord record;
  run({[&](sqlite3* db) {
         if (const auto id = session_id_of(db, subject, session)) {
           Statement owner(db, "SELECT token_hash FROM sessions WHERE id = ?");
           owner.bind(1, *id);
           if (!owner.step() || owner.text(0) != hash) refuse_taken(subject, session);
           record = {*id, subject, session};
           return;
         }
         if (token_taken(db, hash)) refuse_reused_token();
         record = insert_session(db, subject, session, hash);
       },
       [&] { sessions_[hash] = record; },
       {}});
  return record;
}

RowStored StudyDatabase::store_row(const SessionRecord& session, long index,
                                   const std::string& line, const std::string& answer) {
  RowStored stored = RowStored::added;
  run({[&](sqlite3* db) {
         Statement existing(db, "SELECT line FROM rows WHERE session_id = ? AND row_index = ?");
         existing.bind(1, session.id).bind(2, int64_t(index));
         if (existing.step()) {
           if (existing.text(0) != line)
             throw Refusal(409, "conflicting row",
                           "row " + std::to_string(index) + " of " + session.subject +
                               " differs from the row already kept under its key");
           stored = RowStored::repeated;
           return;
         }
         Statement count(db, "SELECT count(*) FROM rows WHERE session_id = ?");
         count.bind(1, session.id);
         if (!count.step() || count.integer(0) != index)
           throw Refusal(409, "row out of order",
                         "row " + std::to_string(index) + " of " + session.subject +
                             " comes before row " + std::to_string(count.integer(0)));
         const std::string now = utc_timestamp();
         Statement insert(db,
                          "INSERT INTO rows(session_id, row_index, line, answer, received) "
                          "VALUES (?, ?, ?, ?, ?)");
         insert.bind(1, session.id).bind(2, int64_t(index)).bind(3, line).bind(4, answer);
         insert.bind(5, now).run();
         Statement touch(db, "UPDATE sessions SET last_activity = ? WHERE id = ?");
         touch.bind(1, now).bind(2, session.id).run();
       },
       {},
       {}});
  return stored;
}

void StudyDatabase::mark_completed(const SessionRecord& session) {
  run({[&](sqlite3* db) {
         Statement done(db, "UPDATE sessions SET completed = 1 WHERE id = ?");
         done.bind(1, session.id).run();
       },
       {},
       {}});
}

std::vector<std::string> StudyDatabase::lines_of(const SessionRecord& session) const {
  Connection reader(file_, true);
  Statement s(reader.get(), "SELECT line FROM rows WHERE session_id = ? ORDER BY row_index");
  s.bind(1, session.id);
  std::vector<std::string> lines;
  while (s.step()) lines.push_back(s.text(0));
  return lines;
}

}  // namespace countershade::serve
