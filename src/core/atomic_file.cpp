#include "core/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <string>

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

}  // namespace countershade
