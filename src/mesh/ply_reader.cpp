#include "mesh/ply_reader.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/mapped_file.h"
#include "mesh/mesh_text.h"

namespace countershade {
namespace {

enum class Format { ascii, little_endian, big_endian };

// A scalar type: its size in bytes and whether it is an integer (and signed).
struct ScalarType {
  int bytes = 0;
  bool integer = false, is_signed = false;
};

std::optional<ScalarType> scalar_type(const std::string& t) {
  if (t == "char" || t == "int8") return ScalarType{1, true, true};
  if (t == "uchar" || t == "uint8") return ScalarType{1, true, false};
  if (t == "short" || t == "int16") return ScalarType{2, true, true};
  if (t == "ushort" || t == "uint16") return ScalarType{2, true, false};
  if (t == "int" || t == "int32") return ScalarType{4, true, true};
  if (t == "uint" || t == "uint32") return ScalarType{4, true, false};
  if (t == "float" || t == "float32") return ScalarType{4, false, true};
  if (t == "double" || t == "float64") return ScalarType{8, false, true};
  return std::nullopt;
}

// What a vertex property becomes.
enum class Role { x, y, z, red, green, blue, skipped };

struct VertexProperty {
  ScalarType type;
  Role role = Role::skipped;
};

// The parts of a header this reader understands.
struct Header {
  Format format = Format::ascii;
  size_t vertices = 0, faces = 0;
  std::vector<VertexProperty> vertex;
  ScalarType count_type, index_type;
  size_t body = 0;  // offset of the first byte after end_header
};

std::optional<Role> vertex_role(const std::string& name, const ScalarType& type) {
  const bool real = !type.integer, byte = type.integer && type.bytes == 1 && !type.is_signed;
  if (real && (name == "x" || name == "y" || name == "z")) return Role(name[0] - 'x');
  if (byte && (name == "red" || name == "green" || name == "blue"))
    return name == "red" ? Role::red : name == "green" ? Role::green : Role::blue;
  if ((byte && name == "alpha") || (real && (name == "nx" || name == "ny" || name == "nz")))
    return Role::skipped;  // what load_mesh does not keep (OpenMesh is not asked for it either)
  return std::nullopt;
}

// One header line into `h`; false for anything this reader does not take.
bool header_line(const std::vector<std::string>& w, Header& h, std::string& element) {
  if (w.empty() || w[0] == "comment" || w[0] == "obj_info") return true;
  if (w[0] == "format" && w.size() == 3) {
    h.format = w[1] == "ascii"                  ? Format::ascii
               : w[1] == "binary_little_endian" ? Format::little_endian
                                                : Format::big_endian;
    return true;
  }
  unsigned long long count = 0;
  if (w[0] == "element" && w.size() == 3 && parse_count(w[2], count)) {
    if (w[1] != (element.empty() ? "vertex" : "face") || element == "face") return false;
    element = w[1];
    (element == "vertex" ? h.vertices : h.faces) = size_t(count);
    return true;
  }
  if (w[0] != "property") return false;
  if (element == "vertex" && w.size() == 3) {
    const auto type = scalar_type(w[1]);
    const auto role = type ? vertex_role(w[2], *type) : std::nullopt;
    if (!role) return false;
    h.vertex.push_back({*type, *role});
    return true;
  }
  const auto count_type = w.size() == 5 ? scalar_type(w[2]) : std::nullopt;
  const auto index_type = w.size() == 5 ? scalar_type(w[3]) : std::nullopt;
  if (element != "face" || w[1] != "list" || !count_type || !index_type || !count_type->integer ||
      !index_type->integer || h.index_type.bytes != 0 ||
      (w[4] != "vertex_indices" && w[4] != "vertex_index"))
    return false;
  h.count_type = *count_type;
  h.index_type = *index_type;
  return true;
}

bool complete(const Header& h) {
  auto has = [&](Role r) {
    return std::count_if(h.vertex.begin(), h.vertex.end(),
                         [r](const VertexProperty& p) { return p.role == r; }) == 1;
  };
  const int colours = int(has(Role::red)) + int(has(Role::green)) + int(has(Role::blue));
  return has(Role::x) && has(Role::y) && has(Role::z) && (colours == 0 || colours == 3) &&
         h.index_type.bytes != 0;
}

std::optional<Header> read_header(std::string_view bytes) {
  Header h;
  std::string element;
  size_t at = 0;
  for (bool first = true;; first = false) {
    const size_t end = bytes.find('\n', at);
    if (end == std::string::npos) return std::nullopt;
    std::string line(bytes.substr(at, end - at));
    at = end + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (first) continue;  // "ply" (checked before)
    if (line == "end_header") break;
    if (!header_line(split_words(line), h, element)) return std::nullopt;
  }
  h.body = at;
  return complete(h) ? std::optional<Header>(h) : std::nullopt;
}

// The values of a body, one at a time, as doubles (exact for every PLY integer and for floats).
class BinaryValues {
 public:
  BinaryValues(std::string_view bytes, size_t at, bool swap)
      : data_(bytes.data()), size_(bytes.size()), at_(at), swap_(swap) {}

  // False when the file ends first.
  bool next(const ScalarType& type, double& value) {
    if (at_ + size_t(type.bytes) > size_) return false;
    unsigned char raw[8];
    std::memcpy(raw, data_ + at_, size_t(type.bytes));
    at_ += size_t(type.bytes);
    if (swap_) std::reverse(raw, raw + type.bytes);
    value = decode(raw, type);
    return true;
  }

 private:
  static double decode(const unsigned char* raw, const ScalarType& type) {
    auto as = [raw]<class T>(T) {
      T v;
      std::memcpy(&v, raw, sizeof v);
      return double(v);
    };
    if (!type.integer) return type.bytes == 4 ? as(float()) : as(double());
    switch (type.bytes) {
      case 1:
        return type.is_signed ? as(int8_t()) : as(uint8_t());
      case 2:
        return type.is_signed ? as(int16_t()) : as(uint16_t());
      default:
        return type.is_signed ? as(int32_t()) : as(uint32_t());
    }
  }

  const char* data_;
  size_t size_, at_;
  bool swap_;
};

// The words of an ASCII body, parsed as their declared type. A float property parses as a float,
// as OpenMesh reads it (and a double as a double).
class AsciiValues {
 public:
  AsciiValues(std::string_view bytes, size_t at)
      : p_(bytes.data() + at), end_(bytes.data() + bytes.size()) {}

  // False when the file ends first or the word is not a number of the type (then OpenMesh reads
  // the file, as before).
  bool next(const ScalarType& type, double& value) {
    while (p_ < end_ && is_blank(*p_)) ++p_;
    const char* word = p_;
    while (p_ < end_ && !is_blank(*p_)) ++p_;
    if (word == p_) return false;
    if (type.integer) return parse<long long>(word, value);
    return type.bytes == 4 ? parse<float>(word, value) : parse<double>(word, value);
  }

 private:
  template <class T>
  bool parse(const char* word, double& value) const {
    T v{};
    const auto [end, error] = std::from_chars(word, p_, v);
    value = double(v);
    return error == std::errc() && end == p_;
  }

  const char* p_;
  const char* end_;
};

// The vertices and faces through `values` (binary or ASCII); none where a value does not parse,
// a colour is not a byte or a face is not a polygon of distinct vertices (OpenMesh then reads it).
template <class Values>
std::optional<PolygonSoup> read_body(const Header& h, Values values, const std::string& file) {
  PolygonSoup soup;
  soup.positions.resize(h.vertices);
  const bool colours = std::any_of(h.vertex.begin(), h.vertex.end(),
                                   [](const VertexProperty& p) { return p.role == Role::red; });
  if (colours) soup.colours.resize(h.vertices);
  double v = 0;
  for (size_t i = 0; i < h.vertices; ++i)
    for (const VertexProperty& p : h.vertex) {
      if (!values.next(p.type, v)) return std::nullopt;
      if (p.role <= Role::z) soup.positions[i][int(p.role)] = float(v);
      if (p.role >= Role::red && p.role <= Role::blue) {
        if (v < 0 || v > 255) return std::nullopt;
        soup.colours[i][int(p.role) - int(Role::red)] = float(v) / 255.0f;
      }
    }
  soup.face_ends.reserve(h.faces);
  soup.corners.reserve(3 * h.faces);
  for (size_t f = 0; f < h.faces; ++f) {
    if (!values.next(h.count_type, v) || v < 3 || v > 1e6) return std::nullopt;
    const size_t begin = soup.corners.size(), n = size_t(v);
    for (size_t k = 0; k < n; ++k) {
      if (!values.next(h.index_type, v)) return std::nullopt;
      if (v < 0 || v >= double(h.vertices))
        throw_input_error(file, "face " + std::to_string(f) + " has a vertex index out of range");
      const unsigned index = unsigned(v);
      for (size_t j = begin; j < soup.corners.size(); ++j)
        if (soup.corners[j] == index) return std::nullopt;  // a repeated vertex
      soup.corners.push_back(index);
    }
    soup.face_ends.push_back(soup.corners.size());
  }
  return soup;
}

}  // namespace

std::optional<PolygonSoup> read_ply_soup(const std::filesystem::path& path) {
  const MappedFile mapped(path);
  const std::string_view bytes = mapped.bytes();
  const auto header = read_header(bytes);
  if (!header) return std::nullopt;
  const std::string file = path.string();
  if (header->format == Format::ascii)
    return read_body(*header, AsciiValues(bytes, header->body), file);
  const bool swap =
      (header->format == Format::big_endian) != (std::endian::native == std::endian::big);
  return read_body(*header, BinaryValues(bytes, header->body, swap), file);
}

}  // namespace countershade
