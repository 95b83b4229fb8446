#pragma once
// Files that appear whole or not at all: write to a temporary sibling, then rename over the target.

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace countershade {

// Calls `write(temporary_path)`, then renames the temporary file to `path`. The temporary path
// keeps the target's extension so format-by-extension writers still work. On any exception the
// temporary file is removed and the exception propagates; `path` is untouched.
void write_atomically(const std::filesystem::path& path,
                      const std::function<void(const std::filesystem::path&)>& write);

// Writes `text` to `path` atomically; throws std::runtime_error when it cannot.
void write_text_atomically(const std::filesystem::path& path, const std::string& text);

// The extension of `path` in lower case, with its dot (".png"); file formats are chosen by it.
std::string lower_extension(const std::filesystem::path& path);

// Checks, before any work, that `path` can become an output file: its extension is one of
// `extensions` (else InputError "<path>: output must be <formats>"), its folder exists and can
// be written, and it is not a folder itself. Returns the extension.
std::string check_output_file(const std::filesystem::path& path,
                              const std::vector<std::string>& extensions,
                              const std::string& formats);

// Checks, before any work, that `folder` is a folder or can become one: not a file, and a file
// can be created in it or in its nearest existing parent. Throws InputError naming it.
void check_output_folder(const std::filesystem::path& folder);

}  // namespace countershade
