#include "core/atomic_file.h"

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
  fs::path temp = dir / ("." + path.stem().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                         std::to_string(counter++) + path.extension().string());
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
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

std::string check_output_file(const std::filesystem::path& path, const std::vector<std::string>& extensions,
                              const std::string& formats) {
  namespace fs = std::filesystem;
  const std::string ext = lower_extension(path);
  if (std::find(extensions.begin(), extensions.end(), ext) == extensions.end())
    throw_input_error(path.string(), "output must be " + formats);
  const fs::path dir = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw_input_error(path.string(), "output folder does not exist");
  if (::access(dir.c_str(), W_OK) != 0) throw_input_error(path.string(), "output folder is not writable");
  if (fs::is_directory(path, ec)) throw_input_error(path.string(), "is a folder, not a file");
  return ext;
}

}  // namespace countershade
