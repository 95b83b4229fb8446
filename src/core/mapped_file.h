#pragma once
// A file mapped read-only into memory, for the readers that parse a large file in one pass: the
// page cache's pages are read in place, with no copy into a buffer and no zero-filling of one
// (docs/performance.md, "Mesh I/O").

#include <filesystem>
#include <string_view>

namespace countershade {

class MappedFile {
 public:
  // Throws InputError "<path>: no such file" or "<path>: cannot read".
  explicit MappedFile(const std::filesystem::path& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  // The file's bytes as they were when it was mapped (empty for an empty file).
  std::string_view bytes() const { return {data_, size_}; }

 private:
  const char* data_ = nullptr;
  size_t size_ = 0;
};

}  // namespace countershade
