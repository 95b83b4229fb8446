#include "mesh/ply_writer.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>

#include "core/atomic_file.h"

namespace countershade {
namespace {

// Bytes gathered in memory and written a block at a time: a stream's per-value writes were most
// of a large mesh's output.
class BlockWriter {
 public:
  explicit BlockWriter(const std::filesystem::path& path)
      : file_(std::fopen(path.c_str(), "wb")), name_(path.string()) {
    if (!file_) throw std::runtime_error(name_ + ": cannot write mesh");
    block_.reserve(kBlock + kLongest);
  }
  ~BlockWriter() {
    if (file_) std::fclose(file_);
  }

  void put(const void* bytes, size_t size) {
    block_.append(static_cast<const char*>(bytes), size);
    if (block_.size() >= kBlock) flush();
  }
  template <class T>
  void put_value(T value) {  // little-endian, as on every machine countershade builds for
    put(&value, sizeof value);
  }
  void put_text(std::string_view text) { put(text.data(), text.size()); }
  // A number in the fewest digits that read back to it, then `separator`.
  template <class T>
  void put_number(T value, char separator) {
    char digits[kLongest];
    char* end = std::to_chars(digits, digits + sizeof digits - 1, value).ptr;
    *end++ = separator;
    put(digits, size_t(end - digits));
  }

  void close() {
    flush();
    const bool failed = std::fclose(file_) != 0;
    file_ = nullptr;
    if (failed) throw std::runtime_error(name_ + ": cannot write mesh");
  }

 private:
  static constexpr size_t kBlock = 1 << 20, kLongest = 64;
  void flush() {
    if (std::fwrite(block_.data(), 1, block_.size(), file_) != block_.size())
      throw std::runtime_error(name_ + ": cannot write mesh");
    block_.clear();
  }

  std::FILE* file_;
  std::string name_, block_;
};

// The largest face decides the list's count type: a byte, as OpenMesh writes it, while every face
// fits one.
bool faces_fit_a_byte(const PolygonSoup& soup) {
  for (size_t f = 0; f < soup.face_count(); ++f)
    if (soup.face(f).size() > 255) return false;
  return true;
}

std::string header(const PolygonSoup& soup, PlyEncoding encoding) {
  std::string h = "ply\nformat ";
  h += encoding == PlyEncoding::binary ? "binary_little_endian" : "ascii";
  h += " 1.0\nelement vertex " + std::to_string(soup.positions.size()) +
       "\nproperty float x\nproperty float y\nproperty float z\n";
  if (!soup.colours.empty()) h += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  h += "element face " + std::to_string(soup.face_count()) + "\nproperty list " +
       (faces_fit_a_byte(soup) ? "uchar" : "int") + " int vertex_indices\nend_header\n";
  return h;
}

void write_binary_body(const PolygonSoup& soup, BlockWriter& out) {
  for (size_t v = 0; v < soup.positions.size(); ++v) {
    out.put(&soup.positions[v], 3 * sizeof(float));
    if (!soup.colours.empty()) {
      const glm::u8vec3 c = colour_bytes(soup.colours[v]);
      out.put(&c, 3);
    }
  }
  const bool byte_counts = faces_fit_a_byte(soup);
  for (size_t f = 0; f < soup.face_count(); ++f) {
    const auto face = soup.face(f);
    byte_counts ? out.put_value(uint8_t(face.size())) : out.put_value(int32_t(face.size()));
    out.put(face.data(), face.size_bytes());
  }
}

void write_ascii_body(const PolygonSoup& soup, BlockWriter& out) {
  for (size_t v = 0; v < soup.positions.size(); ++v) {
    const glm::vec3& p = soup.positions[v];
    const bool colour = !soup.colours.empty();
    out.put_number(p.x, ' ');
    out.put_number(p.y, ' ');
    out.put_number(p.z, colour ? ' ' : '\n');
    if (!colour) continue;
    const glm::u8vec3 c = colour_bytes(soup.colours[v]);
    out.put_number(int(c.x), ' ');
    out.put_number(int(c.y), ' ');
    out.put_number(int(c.z), '\n');
  }
  for (size_t f = 0; f < soup.face_count(); ++f) {
    const auto face = soup.face(f);
    out.put_number(face.size(), ' ');
    for (size_t k = 0; k < face.size(); ++k)
      out.put_number(face[k], k + 1 == face.size() ? '\n' : ' ');
  }
}

}  // namespace

void write_ply(const std::filesystem::path& path, const PolygonSoup& soup, PlyEncoding encoding) {
  write_atomically(path, [&](const std::filesystem::path& temp) {
    BlockWriter out(temp);
    out.put_text(header(soup, encoding));
    encoding == PlyEncoding::binary ? write_binary_body(soup, out) : write_ascii_body(soup, out);
    out.close();
  });
}

}  // namespace countershade
