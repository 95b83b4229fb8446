#include "mesh/ply_check.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "core/error.h"
#include "mesh/mesh_text.h"

namespace countershade {
namespace {

struct PlyProperty {
  bool list = false;
  bool integer = false;  // the values' type (a list's count is always an integer)
};

struct PlyElement {
  std::string name;
  unsigned long long count = 0;
  std::vector<PlyProperty> properties;
};

// What a PLY header has declared so far.
struct PlyHeader {
  std::string format;             // ascii, binary_little_endian or binary_big_endian
  unsigned long long values = 0;  // the sum of the element counts
  std::vector<PlyElement> elements;
};

// 0: not a PLY type, 1: an integer type, 2: a floating-point type.
int ply_type(const std::string& t) {
  static const char* const kIntegers[] = {"char", "uchar", "short", "ushort", "int",   "uint",
                                          "int8", "uint8", "int16", "uint16", "int32", "uint32"};
  static const char* const kFloats[] = {"float", "double", "float32", "float64"};
  auto is = [&](const auto& names) {
    return std::any_of(std::begin(names), std::end(names), [&](const char* k) { return t == k; });
  };
  return is(kIntegers) ? 1 : is(kFloats) ? 2 : 0;
}

// "property TYPE NAME" or "property list COUNT_TYPE TYPE NAME", with known types and an integer
// count.
bool read_ply_property(const std::vector<std::string>& w, PlyProperty& property) {
  if (w.size() == 3 && ply_type(w[1]) != 0) {
    property.integer = ply_type(w[1]) == 1;
    return true;
  }
  if (w.size() != 5 || w[1] != "list" || ply_type(w[2]) != 1 || ply_type(w[3]) == 0) return false;
  property.list = true;
  property.integer = ply_type(w[3]) == 1;
  return true;
}

void check_ply_element(const std::vector<std::string>& w, const std::string& where,
                       PlyHeader& header) {
  unsigned long long count = 0;
  if (w.size() != 3 || !parse_count(w[2], count))
    throw_input_error(where, "expected 'element NAME COUNT'");
  // OpenMesh's reader handles vertex and face elements; it crashed on others (found by the fuzzer).
  if (w[1] != "vertex" && w[1] != "face")
    throw_input_error(where, "element '" + w[1] + "' is not read (only vertex and face)");
  header.values += std::min(count, 1ull << 62);
  header.elements.push_back({w[1], count, {}});
}

// One PLY header line (after the first), which must be printable ASCII with a known keyword.
void check_ply_header_line(const std::string& line, const std::vector<std::string>& w,
                           const std::string& where, PlyHeader& header) {
  if (std::any_of(line.begin(), line.end(),
                  [](char c) { return (c < 0x20 && c != '\t') || c > 0x7e; }))
    throw_input_error(where, "PLY header holds a control or non-ASCII character");
  const std::string keyword = w.empty() ? "" : w[0];
  if (keyword == "format") {
    const bool known =
        w.size() == 3 &&
        (w[1] == "ascii" || w[1] == "binary_little_endian" || w[1] == "binary_big_endian") &&
        w[2] == "1.0";
    if (!known)
      throw_input_error(where,
                        "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
    header.format = w[1];
  } else if (keyword == "element") {
    check_ply_element(w, where, header);
  } else if (keyword == "property") {
    PlyProperty property;
    if (header.elements.empty()) throw_input_error(where, "a property before any element line");
    if (!read_ply_property(w, property))
      throw_input_error(where,
                        "expected 'property TYPE NAME' or 'property list INTEGER_TYPE TYPE NAME'");
    header.elements.back().properties.push_back(property);
  } else if (keyword != "comment" && keyword != "obj_info") {
    throw_input_error(
        where,
        "unexpected PLY header line (expected format, element, property, comment or end_header)");
  }
}

// The words of an ASCII body, from memory: the stream's word-by-word reading was most of a large
// file's check.
class BodyWords {
 public:
  explicit BodyWords(std::string text) : text_(std::move(text)), p_(text_.data()) {}

  // The next word as a number (an integer when `integer`), or an InputError at `where()` (made
  // only then: making it for every element was slow).
  template <class Where>
  double next(bool integer, const Where& where) {
    const char* end = text_.data() + text_.size();
    while (p_ < end && is_blank(*p_)) ++p_;
    const char* word = p_;
    while (p_ < end && !is_blank(*p_)) ++p_;
    if (word == p_) throw_input_error(where(), "the file ends before all its values");
    if (integer) {
      long long whole = 0;
      const auto [stop, error] = std::from_chars(word, p_, whole);
      if (error != std::errc() || stop != p_)
        throw_input_error(where(), "'" + std::string(word, p_) + "' is not an integer");
      return double(whole);
    }
    double value = 0;
    const auto [stop, error] = std::from_chars(word, p_, value);
    if (error == std::errc() && stop == p_) return value;
    if (!parse_number(std::string(word, p_), value))  // strtod's wider syntax ("+1", "nan")
      throw_input_error(where(), "'" + std::string(word, p_) + "' is not a number");
    return value;
  }

 private:
  std::string text_;
  const char* p_;
};

// OpenMesh reads an ASCII body word by word without checking: a stray word made it loop forever.
void check_ply_ascii_body(std::istream& in, const PlyHeader& header, const std::string& file) {
  BodyWords words(std::string(std::istreambuf_iterator<char>(in), {}));
  for (const PlyElement& element : header.elements)
    for (unsigned long long i = 0; i < element.count; ++i) {
      const auto where = [&] { return file + ": " + element.name + " " + std::to_string(i); };
      for (const PlyProperty& property : element.properties) {
        const double count = property.list ? words.next(true, where) : 1;
        if (count < 0) throw_input_error(where(), "a list has a negative length");
        for (double k = 0; k < count; ++k) words.next(property.integer, where);
      }
    }
}

// After end_header: the body must be able to hold the declared elements (one byte each at least).
void check_ply_body(std::ifstream& in, const std::filesystem::path& path, const PlyHeader& header,
                    PlyCheck check) {
  const std::string file = path.string();
  if (header.format.empty()) throw_input_error(file, "PLY header has no format line");
  const auto body = std::filesystem::file_size(path) - std::uintmax_t(in.tellg());
  if (header.values > body)
    throw_input_error(file, "PLY header declares " + std::to_string(header.values) +
                                " elements but only " + std::to_string(body) + " bytes follow it");
  if (header.format == "ascii" && check == PlyCheck::header_and_body)
    check_ply_ascii_body(in, header, file);
}

}  // namespace

void check_ply(const std::filesystem::path& path, PlyCheck check) {
  constexpr std::streamoff kMaxHeader = 1 << 20;
  std::ifstream in(path, std::ios::binary);
  const std::string file = path.string();
  std::string line;
  PlyHeader header;
  for (size_t number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (number == 1) {
      if (line != "ply") throw_input_error(file, "not a PLY file (the first line is not 'ply')");
    } else if (line == "end_header") {
      return check_ply_body(in, path, header, check);
    } else {
      check_ply_header_line(line, split_words(line), file + ": line " + std::to_string(number),
                            header);
    }
    if (in.tellg() > kMaxHeader) break;
  }
  throw_input_error(file, "PLY header has no end_header line");
}

}  // namespace countershade
