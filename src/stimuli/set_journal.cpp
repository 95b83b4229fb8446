#include "stimuli/set_journal.h"

#include <fstream>
#include <vector>

#include "core/error.h"
#include "core/sha256.h"

namespace countershade {

namespace fs = std::filesystem;

SetJournal::SetJournal(const fs::path& path, const std::string& experiment_sha256) {
  std::error_code ec;
  const bool exists = fs::exists(path, ec);
  file_ = AppendOnlyFile::open_or_create(path);
  if (!exists) {
    file_.append(OrderedJson{{"experiment_sha256", experiment_sha256}}.dump() + "\n");
    file_.sync();
  }
}

void SetJournal::append(const ManifestEntry& entry) {
  const std::string line = to_json(entry).dump() + "\n";
  std::lock_guard<std::mutex> lock(mutex_);
  file_.append(line);
  file_.sync();
}

namespace {

[[noreturn]] void refuse_other_experiment(const fs::path& set_dir) {
  throw_input_error(set_dir.string(),
                    "the set there was made from a different experiment file; resume it with that "
                    "file or choose a new folder (nothing was changed)");
}

bool still_there(const fs::path& set_dir, const ManifestEntry& entry) {
  std::error_code ec;
  const fs::path file = resolve_in_set(set_dir, entry.file);
  return fs::is_regular_file(file, ec) && sha256_file(file) == entry.sha256;
}

// Entries of the journal; a line cut by the interruption is skipped.
std::vector<ManifestEntry> journal_entries(const fs::path& set_dir, const fs::path& journal,
                                           const std::string& experiment_sha256) {
  std::vector<ManifestEntry> entries;
  std::ifstream in(journal);
  std::string line;
  while (std::getline(in, line)) {
    OrderedJson entry;
    try {
      entry = OrderedJson::parse(line);
    } catch (const std::exception&) {
      continue;
    }
    if (!entry.is_object()) continue;
    if (entry.contains("experiment_sha256")) {
      if (entry["experiment_sha256"] != experiment_sha256) refuse_other_experiment(set_dir);
      continue;
    }
    try {
      entries.push_back(parse_manifest_entry(entry, journal, entries.size()));
    } catch (const InputError&) {
      continue;  // not a whole entry
    }
  }
  return entries;
}

}  // namespace

std::map<std::string, ManifestEntry> verified_earlier_images(const fs::path& set_dir,
                                                             const fs::path& journal,
                                                             const fs::path& manifest,
                                                             const std::string& experiment_sha256) {
  std::vector<ManifestEntry> candidates;
  std::error_code ec;
  if (fs::exists(manifest, ec)) {
    Manifest finished = read_manifest(manifest);
    if (finished.experiment_sha256 != experiment_sha256) refuse_other_experiment(set_dir);
    candidates = finished.stimuli;
  }
  if (fs::exists(journal, ec)) {
    auto more = journal_entries(set_dir, journal, experiment_sha256);
    candidates.insert(candidates.end(), more.begin(), more.end());
  }
  std::map<std::string, ManifestEntry> done;
  for (auto& entry : candidates)
    if (still_there(set_dir, entry)) done[entry.file] = std::move(entry);
  return done;
}

void remove_interrupted_writes(const fs::path& dir,
                               const std::function<bool(const std::string& file)>& mine) {
  // A run killed while writing leaves its temporary file (".<stem>.tmp-<pid>-<n><ext>", see
  // write_atomically) beside the file it was writing; finished files never have that form.
  std::vector<fs::path> leftovers;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    const size_t tmp = name.find(".tmp-");
    if (!entry.is_regular_file() || name.size() < 2 || name[0] != '.' || tmp == std::string::npos)
      continue;
    const fs::path target = fs::relative(entry.path().parent_path(), dir) /
                            (name.substr(1, tmp - 1) + entry.path().extension().string());
    if (!mine || mine(target.lexically_normal().generic_string()))
      leftovers.push_back(entry.path());
  }
  for (const auto& p : leftovers) fs::remove(p);
}

}  // namespace countershade
