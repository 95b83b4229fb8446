#pragma once
// Files that appear whole or not at all: write to a temporary sibling, then rename over the target.

#include <filesystem>
#include <functional>

namespace countershade {

// Calls `write(temporary_path)`, then renames the temporary file to `path`. The temporary path
// keeps the target's extension so format-by-extension writers still work. On any exception the
// temporary file is removed and the exception propagates; `path` is untouched.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path&)>& write);

}  // namespace countershade
