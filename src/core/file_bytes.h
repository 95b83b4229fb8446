#pragma once
// Reading a whole file into memory.

#include <filesystem>
#include <string>

namespace countershade {

// The file's bytes. Throws InputError "<path>: no such file" or "<path>: cannot read".
std::string read_file_bytes(const std::filesystem::path& path);

}  // namespace countershade
