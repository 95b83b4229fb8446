#pragma once
// An exported study's folder as `serve` hosts it: the study the page runs (study.js, written by
// export-web), the columns of the rows its page POSTs, and the files a request may read.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace countershade::serve {

enum class StudyKind { adjustment, forced_choice };

struct StudyFolder {
  std::filesystem::path root;  // canonical: no symbolic link in it
  nlohmann::json page;         // study.js's object
  StudyKind kind = StudyKind::adjustment;
  std::string set_sha256;
  std::string app_version;  // the version of countershade that exported it
  std::string title;
  std::vector<std::string> columns;  // of every POSTed row, in order
};

// The columns of the rows a study's page POSTs: the app's, then the browser's (web/store.js), and
// in a forced-choice study the interval timing's (web/plugin-choice.js).
std::vector<std::string> posted_columns(StudyKind kind);

// Reads STUDY_DIR/study.js. Throws InputError naming the file and what is wrong.
StudyFolder open_study_folder(const std::filesystem::path& dir);

// The regular file that a request's decoded path names inside the folder ("/" is index.html), or
// none: a path with an empty, "." or ".." segment, a backslash or a control character, a hidden
// name, a symbolic link anywhere below the root, or no such file. Folders are never listed.
std::optional<std::filesystem::path> study_file(const StudyFolder& folder,
                                                const std::string& request_path);

// The Content-Type of a file the page loads, by its extension.
std::string content_type(const std::filesystem::path& file);

// The key under which the page stores a session's rows, and so the prefix of every row's
// Idempotency-Key (web/store.js): "countershade:SET:SUBJECT:SESSION" ("countershade-choice:…").
std::string page_store_key(const StudyFolder& folder, const std::string& subject, int session);

// The name `adjust` or `choose` gives a session's CSV: SUBJECT_sNN.csv (.forced-choice.csv).
std::string session_file_name(StudyKind kind, const std::string& subject, int session);

}  // namespace countershade::serve
