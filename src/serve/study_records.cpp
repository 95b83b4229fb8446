#include "serve/study_records.h"

#include "core/atomic_file.h"
#include "core/error.h"
#include "runtime/study.h"
#include "serve/sqlite.h"
#include "serve/study_folder.h"

namespace countershade::serve {
namespace {

namespace fs = std::filesystem;

std::string value_of(sqlite3* db, const char* key) {
  Statement s(db, "SELECT value FROM study WHERE key = ?");
  s.bind(1, std::string(key));
  return s.step() ? s.text(0) : "";
}

// A connection that only reads; the file must exist (SQLite would create an empty one).
Connection open_existing(const fs::path& database) {
  if (!fs::is_regular_file(database)) throw_input_error(database.string(), "no such database");
  return Connection(database, true);
}

void read_sessions(sqlite3* db, StudyRecords& records, int64_t expected, double abandoned_s) {
  Statement s(db,
              "SELECT subject, session, started, last_activity, "
              "  (SELECT count(*) FROM rows WHERE session_id = id), "
              "  (SELECT count(DISTINCT answer) FROM rows WHERE session_id = id), "
              "  (julianday('now') - julianday(last_activity)) * 86400.0 > ?, completed "
              "FROM sessions ORDER BY id");
  s.bind(1, int64_t(abandoned_s));
  while (s.step()) {
    SessionState state{s.text(0),    int(s.integer(1)), "",       s.integer(4),
                       s.integer(5), s.text(2),         s.text(3)};
    const bool completed = s.integer(7) || (expected > 0 && state.answers >= expected);
    state.state = completed ? "completed" : s.integer(6) ? "abandoned" : "started";
    records.sessions.push_back(std::move(state));
  }
}

}  // namespace

StudyRecords read_records(const fs::path& database, int64_t expected, double abandoned_s) {
  try {
    Connection connection = open_existing(database);
    sqlite3* db = connection.get();
    StudyRecords records;
    records.title = value_of(db, "title");
    records.set_sha256 = value_of(db, "set_sha256");
    records.app_version = value_of(db, "app_version");
    records.kind = value_of(db, "kind");
    Statement links(db, "SELECT count(*), count(claimed_by) FROM links");
    if (links.step()) records.links = links.integer(0), records.links_claimed = links.integer(1);
    read_sessions(db, records, expected, abandoned_s);
    return records;
  } catch (const SqliteError& e) {
    throw_input_error(database.string(), std::string("not a study database (") + e.what() + ")");
  }
}

size_t export_sessions(const fs::path& database, const fs::path& folder) {
  try {
    Connection connection = open_existing(database);
    sqlite3* db = connection.get();
    const std::string header = value_of(db, "columns");
    if (header.empty()) throw_input_error(database.string(), "holds no study");
    const StudyKind kind =
        value_of(db, "kind") == "forced_choice" ? StudyKind::forced_choice : StudyKind::adjustment;
    std::error_code ec;
    fs::create_directories(folder, ec);
    if (ec) throw_input_error(folder.string(), "cannot create the folder");
    // One snapshot for the whole export, even while the server writes.
    connection.execute("BEGIN");
    Statement s(db,
                "SELECT subject, session, line FROM rows JOIN sessions ON id = session_id "
                "ORDER BY id, row_index");
    size_t files = 0;
    std::string current, text;
    const auto flush = [&] {
      if (current.empty()) return;
      write_text_atomically(folder / current, text);
      ++files;
    };
    while (s.step()) {
      runtime::check_subject_id(s.text(0));  // a file name: never a path out of the folder
      const std::string name = session_file_name(kind, s.text(0), int(s.integer(1)));
      if (name != current) flush(), current = name, text = header;
      text += s.text(2);
    }
    flush();
    connection.execute("COMMIT");
    return files;
  } catch (const SqliteError& e) {
    throw_input_error(database.string(), std::string("not a study database (") + e.what() + ")");
  }
}

}  // namespace countershade::serve
