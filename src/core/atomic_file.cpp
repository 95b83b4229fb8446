#include "core/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <fstream>
#include <stdexcept>
#include <string>

#include "core/error.h"

namespace countershade {

void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path&)>& write) {
  namespace fs = std::filesystem;
  static std::atomic<unsigned> counter{0};
  fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  // Appended piece by piece: GCC 12 falsely warns of a 2^63-byte copy where a literal is put in
  // front of a temporary string, depending on how it inlines.
  std::string name = ".";
  name += path.stem().string();
  name += ".tmp-";
  name += std::to_string(::getpid());
  name += '-';
  name += std::to_string(counter++);
  name += path.extension().string();
  const fs::path temp = dir / name;
  try {
    write(temp);
    fs::rename(temp, path);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw;
  }
}

void write_text_atomically(const std::filesystem::path& path, const std::string& text) {
  write_atomically(path, [&](const std::filesystem::path& temp) {
    std::ofstream out(temp, std::ios::binary);
    out << text;
    if (!out.flush()) throw std::runtime_error(path.string() + ": cannot write");
  });
}

std::string lower_extension(const std::filesystem::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

namespace {

// Whether a file can be created in `dir`: tried, since permissions alone do not tell (root,
// read-only mounts, /proc).
bool can_create_in(const std::filesystem::path& dir) {
  const std::filesystem::path probe = dir / (".countershade-probe-" + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_CREAT | O_EXCL | O_WRONLY, 0600);
  if (fd < 0) return false;
  ::close(fd);
  ::unlink(probe.c_str());
  return true;
}

}  // namespace

void check_output_folder(const std::filesystem::path& folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(folder, ec) && !fs::is_directory(folder, ec))
    throw_input_error(folder.string(), "is a file, not a folder");
  fs::path existing = fs::absolute(folder, ec);
  while (existing.has_parent_path() && existing != existing.parent_path() &&
         !fs::exists(existing, ec))
    existing = existing.parent_path();
  if (!fs::is_directory(existing, ec))
    throw_input_error(folder.string(),
                      "cannot create the folder (" + existing.string() + " is not a folder)");
  if (!can_create_in(existing))
    throw_input_error(folder.string(), "cannot write in " + existing.string());
}

std::string check_output_file(const std::filesystem::path& path,
                              const std::vector<std::string>& extensions,
                              const std::string& formats) {
  namespace fs = std::filesystem;
  const std::string ext = lower_extension(path);
  if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end())
    throw_input_error(path.string(), "output must be " + formats);
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw_input_error(path.string(), "output folder does not exist");
  if (!can_create_in(dir)) throw_input_error(path.string(), "output folder is not writable");
  if (fs::is_directory(path, ec)) throw_input_error(path.string(), "is a folder, not a file");
  return ext;
}

}  // namespace countershade
