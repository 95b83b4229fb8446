#pragma once
// A file that only grows, written with write(2) so that a killed process leaves whole lines
// behind: session responses, trajectories and the stimulus-set journal.

#include <filesystem>
#include <string>

namespace countershade {

class AppendOnlyFile {
 public:
  AppendOnlyFile() = default;
  // Creates the file, failing if it exists (InputError), and writes `header` durably.
  static AppendOnlyFile create(const std::filesystem::path& path, const std::string& header);
  // Opens an existing file for appending.
  static AppendOnlyFile open_existing(const std::filesystem::path& path);
  // Opens the file for appending, creating it when it does not exist.
  static AppendOnlyFile open_or_create(const std::filesystem::path& path);
  // Opens a session's file to resume it. A file that is missing or empty gets `header` first,
  // durably: a session killed after writing its sidecar and before its first line left it so.
  static AppendOnlyFile open_to_resume(const std::filesystem::path& path,
                                       const std::string& header);
  AppendOnlyFile(AppendOnlyFile&& other) noexcept;
  AppendOnlyFile& operator=(AppendOnlyFile&& other) noexcept;
  AppendOnlyFile(const AppendOnlyFile&) = delete;
  AppendOnlyFile& operator=(const AppendOnlyFile&) = delete;
  ~AppendOnlyFile();

  void append(const std::string& text);  // one write() call; throws on a short write
  void sync();                           // fsync
  const std::filesystem::path& path() const { return path_; }

 private:
  int fd_ = -1;
  std::filesystem::path path_;
};

// fsyncs a folder, so a file created in it survives a power loss.
void sync_directory(const std::filesystem::path& dir);

}  // namespace countershade
