#pragma once
// The journal of a stimulus set being made: one line per finished image, fsync'd, so a killed run
// loses at most the images in flight, and --resume keeps every image whose checksum still
// matches. Its first line names the experiment it belongs to.

#include <filesystem>
#include <functional>
#include <map>
#include <mutex>
#include <string>

#include "core/append_file.h"
#include "formats/manifest.h"

namespace countershade {

class SetJournal {
 public:
  // Opens (or creates, writing the experiment line) the journal for appending.
  SetJournal(const std::filesystem::path& path, const std::string& experiment_sha256);
  void append(const ManifestEntry& entry);  // thread-safe; durable on return

 private:
  AppendOnlyFile file_;
  std::mutex mutex_;
};

// The images of an earlier run that are still there with their checksums: from its journal and,
// for a finished set, from its manifest. Refuses (InputError, nothing changed) a folder whose
// journal or manifest was made from another experiment file.
std::map<std::string, ManifestEntry> verified_earlier_images(const std::filesystem::path& set_dir,
                                                             const std::filesystem::path& journal,
                                                             const std::filesystem::path& manifest,
                                                             const std::string& experiment_sha256);

// Removes the temporary files of writes that an interruption cut short, of the files (paths
// relative to `dir`) that `mine` accepts: a shard leaves alone those of the shards that may be
// running beside it in the same folder.
void remove_interrupted_writes(const std::filesystem::path& dir,
                               const std::function<bool(const std::string& file)>& mine = {});

}  // namespace countershade
