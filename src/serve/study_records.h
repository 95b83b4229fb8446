#pragma once
// What the lab reads from a study's database, while the study runs or after: the state of every
// session, and each session's rows as the CSV that `adjust` or `choose` would have written. Both
// read through a connection of their own, beside the server's writer (WAL lets them).

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace countershade::serve {

struct SessionState {
  std::string subject;
  int session = 1;
  std::string state;  // "completed", "started" or "abandoned"
  int64_t rows = 0;
  int64_t answers = 0;  // distinct answers of the plan
  std::string started, last_activity;
};

struct StudyRecords {
  std::string title, set_sha256, app_version, kind;
  int64_t links = 0, links_claimed = 0;
  std::vector<SessionState> sessions;  // in the order they started
};

// The sessions' states: completed once every answer of the plan is in (`answers_expected`, 0 for
// a study whose procedures decide its length) or the server marked it so (a forced-choice session
// whose run finished), abandoned after `abandoned_after_s` seconds
// without a row, started otherwise. Throws InputError for a file that is no study database.
StudyRecords read_records(const std::filesystem::path& database, int64_t answers_expected,
                          double abandoned_after_s);

// Writes SUBJECT_sNN.csv (.forced-choice.csv) per session with rows into `folder`: the study's
// header and every row in the order the page sent them. Returns the number of files.
size_t export_sessions(const std::filesystem::path& database, const std::filesystem::path& folder);

}  // namespace countershade::serve
