#pragma once
// The SQLite file that holds one hosted study: its identity (the set's sha256 and the export's
// version), the participant links, the sessions with their token hashes, and every row. All
// writes go through one writer thread that commits what has queued up in one transaction (a group
// commit) with synchronous=FULL in WAL mode: a write's future is fulfilled only once its
// transaction is durable.

#include <condition_variable>
#include <deque>
#include <filesystem>
#include <functional>
#include <future>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "serve/sqlite.h"
#include "serve/study_folder.h"

namespace countershade::serve {

struct SessionRecord {
  int64_t id = 0;
  std::string subject;
  int session = 1;
};

struct NewLink {
  std::string subject;
  int session = 1;
  std::string token;  // only here: the database keeps its hash
};

enum class RowStored { added, repeated };

class StudyDatabase {
 public:
  // Who opens the database: the server, which holds it alone, or a command beside it (adding
  // links), which SQLite's own locking lets write while the server runs.
  enum class Holder { server, beside_server };

  // Opens or creates `file` for the study. Throws InputError when the file holds another study
  // (another set or export version), is no database, or (for a server) another server holds it.
  StudyDatabase(const std::filesystem::path& file, const StudyFolder& folder,
                Holder holder = Holder::server);
  ~StudyDatabase();
  StudyDatabase(const StudyDatabase&) = delete;
  StudyDatabase& operator=(const StudyDatabase&) = delete;

  // Adds `count` one-time links for subjects PREFIX001, PREFIX002, … (numbered after the links
  // already there), session 1.
  std::vector<NewLink> add_links(int count, const std::string& prefix);

  // The session whose token hash this is, if any (from memory: no query).
  std::optional<SessionRecord> session_of(const std::string& token_hash) const;

  // Claims a link for the browser holding `token_hash`. The same browser claiming it again gets
  // its session back. Throws Refusal: 403 for an unknown link, 410 for a link another browser
  // has claimed.
  SessionRecord claim_link(const std::string& link_hash, const std::string& token_hash);
  // Opens a session in open mode; the same token gets its session back. Throws Refusal 409 when
  // another token holds that subject's session.
  SessionRecord open_session(const std::string& subject, int session,
                             const std::string& token_hash);

  // Stores row `index` of a session once it is durable. A repeat of the row under that index is
  // `repeated`; throws Refusal 409 for a different row under a used index, or an index past the
  // next one. `answer` names the plan's answer the row gives (SessionPlan::check).
  RowStored store_row(const SessionRecord& session, long index, const std::string& line,
                      const std::string& answer);

  // Marks a session completed (a forced-choice session whose run has finished).
  void mark_completed(const SessionRecord& session);
  // The rows stored in a session, in order, as CSV lines (read beside the writer).
  std::vector<std::string> lines_of(const SessionRecord& session) const;

  bool has_links() const;
  const std::filesystem::path& file() const { return file_; }

 private:
  struct Job {
    std::function<void(sqlite3*)> work;  // throws Refusal without writing
    std::function<void()> after_commit;  // updates the caches
    std::promise<void> done;
  };
  void run(Job job);
  void writer_loop();
  void commit_batch(std::vector<Job>& batch);
  void create_or_check(const StudyFolder& folder);
  void load_sessions();
  SessionRecord insert_session(sqlite3* db, const std::string& subject, int session,
                               const std::string& token_hash);

  std::filesystem::path file_;
  int lock_ = -1;  // the file, locked (flock) while this server holds it; closed last
  Connection connection_;
  mutable std::mutex mutex_;  // guards the queue and the caches
  std::condition_variable queued_;
  std::deque<Job> queue_;
  bool stopping_ = false;
  std::map<std::string, SessionRecord> sessions_;  // by token hash
  bool has_links_ = false;
  std::thread writer_;
};

}  // namespace countershade::serve
