#include "mesh/mesh_file_check.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "mesh/mesh_text.h"

namespace countershade {
namespace {

// Every word of a line as a number; a word that is not wholly a number is an error (OpenMesh's
// reader stops at it and drops the vertex, so its vertex count would differ from ours).
std::vector<double> obj_numbers(const std::string& rest, const std::string& where) {
  std::vector<double> values;
  std::istringstream words(rest);
  for (std::string w; words >> w;) {
    double v = 0;
    if (!parse_number(w, v)) throw_input_error(where, "'" + w + "' is not a number");
    values.push_back(v);
  }
  return values;
}

// "v x y z [r g b]": three finite coordinates and, when a colour follows, its channels in [0, 1]
// (OpenMesh converts them to bytes unchecked).
void check_obj_vertex(const std::string& rest, const std::string& where, long long index) {
  const std::vector<double> values = obj_numbers(rest, where);
  const std::string vertex = "vertex " + std::to_string(index);
  if (values.size() < 3) throw_input_error(where, vertex + " has fewer than 3 coordinates");
  // Positions are stored as float: a value beyond float's range would become infinite.
  for (size_t k = 0; k < values.size(); ++k)
    if (!(std::abs(values[k]) <= 1e38)) throw_input_error(where, vertex + " has a NaN or infinite " + (k < 3 ? "coordinate" : "value"));
  if (values.size() >= 6 && std::any_of(values.begin() + 3, values.begin() + 6, [](double c) { return c < 0 || c > 1; }))
    throw_input_error(where, vertex + " has a colour outside [0, 1]");
}

// "vt u v [w]": finite numbers (a NaN would reach the texture lookup).
void check_obj_texcoord(const std::string& rest, const std::string& where, long long index) {
  const std::vector<double> values = obj_numbers(rest, where);
  if (values.size() < 2 || !std::isfinite(values[0]) || !std::isfinite(values[1]))
    throw_input_error(where, "texture coordinate " + std::to_string(index) + " needs two finite numbers");
}

// One corner of a face ("v", "v/vt", "v/vt/vn", "v//vn"): its vertex index resolved (1-based,
// negative from the end), after checking both indices against what the file has defined so far.
long long obj_corner(const std::string& corner, const std::string& where, const long long (&defined)[3]) {
  long long index[3] = {0, 0, 0};
  size_t start = 0;
  for (int k = 0; k < 3 && start <= corner.size(); ++k) {
    const size_t end = corner.find('/', start);
    const std::string part = corner.substr(start, end == std::string::npos ? end : end - start);
    if (!part.empty()) {
      // The whole field must be an integer: OpenMesh reads "1x" differently from us.
      const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), index[k]);
      if (error != std::errc() || end != part.data() + part.size() || index[k] == 0)
        throw_input_error(where, "face index '" + part + "' is not a non-zero integer");
    }
    if (end == std::string::npos) break;
    start = end + 1;
  }
  const char* names[3] = {"vertex", "texture coordinate", "normal"};
  for (int k = 0; k < 3; ++k) {
    const long long i = index[k];
    if (k > 0 && i == 0) continue;  // no texture coordinate or normal given
    const long long resolved = i < 0 ? defined[k] + i + 1 : i;
    if (i == 0 || resolved < 1 || resolved > defined[k])
      throw_input_error(where, std::string("face ") + names[k] + " index " + std::to_string(i) + " is out of range (1.." +
                                   std::to_string(defined[k]) + ")");
  }
  return index[0] < 0 ? defined[0] + index[0] + 1 : index[0];
}

// "f c1 c2 c3 ...": at least three corners, each vertex once. Returns its triangle count.
size_t check_obj_face(const std::string& rest, const std::string& where, const long long (&defined)[3]) {
  std::istringstream fields(rest);
  std::vector<long long> face;
  for (std::string corner; fields >> corner;) face.push_back(obj_corner(corner, where, defined));
  std::sort(face.begin(), face.end());
  if (std::adjacent_find(face.begin(), face.end()) != face.end())
    throw_input_error(where, "face is degenerate (a vertex appears twice)");
  if (face.size() < 3) throw_input_error(where, "face has fewer than 3 vertices");
  return face.size() - 2;
}

// OpenMesh's OBJ reader skips vertices it cannot parse and faces with bad indices, printing only
// a warning; check the file first so such meshes are errors with a line number. Returns the
// number of triangles the file describes after fan triangulation.
size_t check_obj(const std::filesystem::path& path) {
  std::ifstream in(path);
  long long defined[3] = {0, 0, 0};  // vertices, texture coordinates, normals so far
  size_t triangles = 0;
  std::string line;
  for (size_t number = 1; std::getline(in, line); ++number) {
    // The keyword as OpenMesh reads it: the first word, after any whitespace (tabs, form feeds).
    std::istringstream fields(line);
    std::string keyword, rest;
    fields >> keyword;
    std::getline(fields, rest);
    const std::string where = path.string() + ": line " + std::to_string(number);
    if (keyword == "v") check_obj_vertex(rest, where, defined[0]++);
    else if (keyword == "vt") check_obj_texcoord(rest, where, defined[1]++);
    else if (keyword == "vn") ++defined[2];
    else if (keyword == "f") triangles += check_obj_face(rest, where, defined);
  }
  return triangles;
}

bool is_ply_type(const std::string& t) {
  static const char* const kTypes[] = {"char",  "uchar",  "short",   "ushort",  "int",     "uint",    "float",
                                       "double", "int8",  "uint8",   "int16",   "uint16",  "int32",   "uint32",
                                       "float32", "float64"};
  return std::find_if(std::begin(kTypes), std::end(kTypes), [&](const char* k) { return t == k; }) != std::end(kTypes);
}

// "property TYPE NAME" or "property list COUNT_TYPE TYPE NAME", with known types.
bool is_ply_property(const std::vector<std::string>& w) {
  if (w.size() == 3) return is_ply_type(w[1]);
  return w.size() == 5 && w[1] == "list" && is_ply_type(w[2]) && is_ply_type(w[3]);
}

// One PLY header line (after the first), which must be printable ASCII with a known keyword.
// What a PLY header has declared so far.
struct PlyHeader {
  bool format = false;
  unsigned long long elements = 0;  // the sum of the element counts
  bool element = false;             // an element line came (properties belong to the last one)
};

void check_ply_header_line(const std::string& line, const std::vector<std::string>& w, const std::string& where,
                           PlyHeader& header) {
  if (std::any_of(line.begin(), line.end(), [](char c) { return (c < 0x20 && c != '\t') || c > 0x7e; }))
    throw_input_error(where, "PLY header holds a control or non-ASCII character");
  const std::string keyword = w.empty() ? "" : w[0];
  if (keyword == "format") {
    header.format = w.size() == 3 && (w[1] == "ascii" || w[1] == "binary_little_endian" || w[1] == "binary_big_endian") &&
                    w[2] == "1.0";
    if (!header.format) throw_input_error(where, "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
  } else if (keyword == "element") {
    unsigned long long count = 0;
    if (w.size() != 3 || !parse_count(w[2], count)) throw_input_error(where, "expected 'element NAME COUNT'");
    // OpenMesh's reader handles vertex and face elements; it crashed on others (found by the fuzzer).
    if (w[1] != "vertex" && w[1] != "face") throw_input_error(where, "element '" + w[1] + "' is not read (only vertex and face)");
    header.elements += std::min(count, 1ull << 62);
    header.element = true;
  } else if (keyword == "property") {
    if (!header.element) throw_input_error(where, "a property before any element line");
    if (!is_ply_property(w)) throw_input_error(where, "expected 'property TYPE NAME' or 'property list TYPE TYPE NAME'");
  } else if (keyword != "comment" && keyword != "obj_info") {
    throw_input_error(where, "unexpected PLY header line (expected format, element, property, comment or end_header)");
  }
}

// The PLY header: "ply", a known format, elements with counts the file can hold, and end_header
// within the first megabyte.
void check_ply(const std::filesystem::path& path) {
  constexpr std::streamoff kMaxHeader = 1 << 20;
  std::ifstream in(path, std::ios::binary);
  const std::string file = path.string();
  std::string line;
  PlyHeader header;
  for (size_t number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string where = file + ": line " + std::to_string(number);
    const std::vector<std::string> w = split_words(line);
    if (number == 1) {
      if (line != "ply") throw_input_error(file, "not a PLY file (the first line is not 'ply')");
    } else if (line == "end_header") {
      if (!header.format) throw_input_error(file, "PLY header has no format line");
      const auto body = std::filesystem::file_size(path) - std::uintmax_t(in.tellg());
      if (header.elements > body)
        throw_input_error(file, "PLY header declares " + std::to_string(header.elements) + " elements but only " +
                                    std::to_string(body) + " bytes follow it");
      return;
    } else {
      check_ply_header_line(line, w, where, header);
    }
    if (in.tellg() > kMaxHeader) break;
  }
  throw_input_error(file, "PLY header has no end_header line");
}

// STL: binary when the size is 84 + 50 bytes per triangle as the header says, else ASCII ('solid').
void check_stl(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  char head[84] = {};
  in.read(head, sizeof head);
  const auto size = std::filesystem::file_size(path);
  uint32_t triangles = 0;
  std::memcpy(&triangles, head + 80, 4);  // little-endian, as on every machine countershade builds for
  if (size >= 84 && size == 84 + 50 * std::uintmax_t(triangles)) return;
  if (std::string_view(head, std::min<size_t>(size, 5)) != "solid")
    throw_input_error(path.string(), "neither a binary STL (84 + 50 bytes per triangle) nor an ASCII STL ('solid')");
}

}  // namespace

size_t check_mesh_file_structure(const std::filesystem::path& path, const std::string& ext) {
  if (ext == ".obj") return check_obj(path);
  if (ext == ".ply") check_ply(path);
  if (ext == ".stl") check_stl(path);
  return 0;
}

}  // namespace countershade
