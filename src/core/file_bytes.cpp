#include "core/file_bytes.h"

#include <fstream>
#include <sstream>

#include "core/error.h"

namespace countershade {

std::string read_file_bytes(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw_input_error(path.string(), "no such file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw_input_error(path.string(), "cannot read");
  std::stringstream bytes;
  bytes << in.rdbuf();  // an empty file only sets the failbit of `bytes`
  if (in.bad()) throw_input_error(path.string(), "cannot read");
  return bytes.str();
}

}  // namespace countershade
