#include "serve/study_folder.h"

#include <sys/stat.h>

#include <map>

#include "core/error.h"
#include "core/file_bytes.h"
#include "forced_choice/choice_row.h"
#include "formats/responses.h"

namespace countershade::serve {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr std::string_view kStudyPrefix = "window.COUNTERSHADE_STUDY = ";

// The columns the page adds after the app's (web/store.js's BROWSER_COLUMNS), and a temporal
// forced-choice trial's after those (web/plugin-choice.js's TIMING_COLUMNS).
const std::vector<std::string> kBrowserColumns = {
    "device_pixel_ratio", "window_width",        "window_height", "refresh_hz", "user_agent",
    "css_px_per_mm",      "viewing_distance_mm", "stimulus_bits", "output_path"};
const std::vector<std::string> kTimingColumns = {"interval_ms", "interval_timing"};

json parse_study_js(const fs::path& file) {
  if (!fs::is_regular_file(file))
    throw_input_error(file.string(), "missing (is this a folder written by export-web?)");
  const std::string text = read_file_bytes(file);
  if (text.rfind(kStudyPrefix, 0) != 0)
    throw_input_error(file.string(), "is not a study written by export-web");
  const size_t end = text.find_last_of(';');
  const json page =
      json::parse(text.substr(kStudyPrefix.size(), end - kStudyPrefix.size()), nullptr, false);
  if (page.is_discarded() || !page.is_object() ||
      page.value("format", "") != "countershade-web-study")
    throw_input_error(file.string(), "is not a study written by export-web");
  return page;
}

// A segment a request may name: no traversal, no hidden file, nothing a shell or a file system
// reads specially.
bool plain_segment(const std::string& s) {
  if (s.empty() || s[0] == '.') return false;
  for (unsigned char c : s)
    if (c < 0x20 || c == 0x7f || c == '\\' || c == ':') return false;
  return true;
}

}  // namespace

std::vector<std::string> posted_columns(StudyKind kind) {
  std::vector<std::string> columns =
      kind == StudyKind::adjustment ? response_columns() : forced_choice::choice_columns();
  columns.insert(columns.end(), kBrowserColumns.begin(), kBrowserColumns.end());
  if (kind == StudyKind::forced_choice)
    columns.insert(columns.end(), kTimingColumns.begin(), kTimingColumns.end());
  return columns;
}

StudyFolder open_study_folder(const fs::path& dir) {
  std::error_code ec;
  StudyFolder folder;
  folder.root = fs::canonical(dir, ec);
  if (ec || !fs::is_directory(folder.root)) throw_input_error(dir.string(), "not a folder");
  const fs::path file = folder.root / "study.js";
  folder.page = parse_study_js(file);
  try {
    folder.kind = folder.page.value("study", "adjustment") == "forced_choice"
                      ? StudyKind::forced_choice
                      : StudyKind::adjustment;
    folder.set_sha256 = folder.page.at("set").at("sha256").get<std::string>();
    folder.app_version = folder.page.at("app_version").get<std::string>();
    folder.title = folder.page.value("title", "");
    folder.page.at("conditions").at(0);
  } catch (const json::exception&) {
    throw_input_error(file.string(), "lacks the set, its version or its conditions");
  }
  folder.columns = posted_columns(folder.kind);
  return folder;
}

std::optional<fs::path> study_file(const StudyFolder& folder, const std::string& request_path) {
  if (request_path.empty() || request_path[0] != '/') return std::nullopt;
  const std::string relative = request_path == "/" ? "index.html" : request_path.substr(1);
  fs::path file = folder.root;
  size_t start = 0;
  while (start <= relative.size()) {
    const size_t slash = std::min(relative.find('/', start), relative.size());
    const std::string segment = relative.substr(start, slash - start);
    if (!plain_segment(segment)) return std::nullopt;
    file /= segment;
    struct stat info;
    if (::lstat(file.c_str(), &info) != 0 || S_ISLNK(info.st_mode)) return std::nullopt;
    if (slash == relative.size()) return S_ISREG(info.st_mode) ? std::optional(file) : std::nullopt;
    if (!S_ISDIR(info.st_mode)) return std::nullopt;
    start = slash + 1;
  }
  return std::nullopt;
}

std::string content_type(const fs::path& file) {
  static const std::map<std::string, std::string> types = {
      {".html", "text/html; charset=utf-8"},
      {".js", "text/javascript; charset=utf-8"},
      {".mjs", "text/javascript; charset=utf-8"},
      {".css", "text/css; charset=utf-8"},
      {".png", "image/png"},
      {".wasm", "application/wasm"},
      {".json", "application/json"},
      {".svg", "image/svg+xml"},
      {".bin", "application/octet-stream"}};
  const auto found = types.find(file.extension().string());
  return found == types.end() ? "application/octet-stream" : found->second;
}

std::string page_store_key(const StudyFolder& folder, const std::string& subject, int session) {
  const char* name = folder.kind == StudyKind::adjustment ? "countershade" : "countershade-choice";
  return std::string(name) + ":" + folder.set_sha256 + ":" + subject + ":" +
         std::to_string(session);
}

std::string session_file_name(StudyKind kind, const std::string& subject, int session) {
  const std::string number = (session < 10 ? "0" : "") + std::to_string(session);
  return subject + "_s" + number + (kind == StudyKind::forced_choice ? ".forced-choice" : "") +
         ".csv";
}

}  // namespace countershade::serve
