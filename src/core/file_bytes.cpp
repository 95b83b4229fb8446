#include "core/file_bytes.h"

#include <fstream>
#include <iterator>

#include "core/error.h"

namespace countershade {

std::string read_file_bytes(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw_input_error(path.string(), "no such file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw_input_error(path.string(), "cannot read");
  // Read into a string of the file's size, in one call: a string stream copies a large mesh twice.
  // A file that grows meanwhile is read to its end.
  std::string bytes(std::filesystem::file_size(path, ec), '\0');
  in.read(bytes.data(), std::streamsize(bytes.size()));
  bytes.resize(size_t(in.gcount()));
  if (in.bad()) throw_input_error(path.string(), "cannot read");
  if (in) bytes.append(std::istreambuf_iterator<char>(in), {});
  if (in.bad()) throw_input_error(path.string(), "cannot read");
  return bytes;
}

}  // namespace countershade
