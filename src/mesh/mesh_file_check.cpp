#include "mesh/mesh_file_check.h"

#include <algorithm>
#include <cctype>
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
#include "mesh/ply_check.h"

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
    if (!(std::abs(values[k]) <= 1e38))
      throw_input_error(where,
                        vertex + " has a NaN or infinite " + (k < 3 ? "coordinate" : "value"));
  if (values.size() >= 6 &&
      std::any_of(values.begin() + 3, values.begin() + 6, [](double c) { return c < 0 || c > 1; }))
    throw_input_error(where, vertex + " has a colour outside [0, 1]");
}

// "vt u v [w]": finite numbers (a NaN would reach the texture lookup).
void check_obj_texcoord(const std::string& rest, const std::string& where, long long index) {
  const std::vector<double> values = obj_numbers(rest, where);
  if (values.size() < 2 || !std::isfinite(values[0]) || !std::isfinite(values[1]))
    throw_input_error(where,
                      "texture coordinate " + std::to_string(index) + " needs two finite numbers");
}

// One corner of a face ("v", "v/vt", "v/vt/vn", "v//vn"): its vertex index resolved (1-based,
// negative from the end), after checking both indices against what the file has defined so far.
long long obj_corner(const std::string& corner, const std::string& where,
                     const long long (&defined)[3]) {
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
      throw_input_error(where, std::string("face ") + names[k] + " index " + std::to_string(i) +
                                   " is out of range (1.." + std::to_string(defined[k]) + ")");
  }
  return index[0] < 0 ? defined[0] + index[0] + 1 : index[0];
}

// "f c1 c2 c3 ...": at least three corners, each vertex once. Returns its triangle count.
size_t check_obj_face(const std::string& rest, const std::string& where,
                      const long long (&defined)[3]) {
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
    // The keyword as OpenMesh reads it: the line trimmed of spaces, tabs, CR and LF; skipped when
    // it then starts with other whitespace (a vertical tab, a form feed), else its first word. A
    // vertex OpenMesh skips but we counted would let a face reach past its vertices.
    const size_t start = line.find_first_not_of(" \t\r\n");
    if (start == std::string::npos || std::isspace(static_cast<unsigned char>(line[start])))
      continue;
    std::istringstream fields(line.substr(start));
    std::string keyword, rest;
    fields >> keyword;
    std::getline(fields, rest);
    const std::string where = path.string() + ": line " + std::to_string(number);
    if (keyword == "v")
      check_obj_vertex(rest, where, defined[0]++);
    else if (keyword == "vt")
      check_obj_texcoord(rest, where, defined[1]++);
    else if (keyword == "vn")
      ++defined[2];
    else if (keyword == "f")
      triangles += check_obj_face(rest, where, defined);
  }
  return triangles;
}

// STL: binary when the size is 84 + 50 bytes per triangle as the header says, else ASCII ('solid').
void check_stl(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  char head[84] = {};
  in.read(head, sizeof head);
  const auto size = std::filesystem::file_size(path);
  uint32_t triangles = 0;
  std::memcpy(&triangles, head + 80,
              4);  // little-endian, as on every machine countershade builds for
  if (size >= 84 && size == 84 + 50 * std::uintmax_t(triangles)) return;
  if (std::string_view(head, std::min<size_t>(size, 5)) != "solid")
    throw_input_error(
        path.string(),
        "neither a binary STL (84 + 50 bytes per triangle) nor an ASCII STL ('solid')");
}

}  // namespace

size_t check_mesh_file_structure(const std::filesystem::path& path, const std::string& ext) {
  if (ext == ".obj") return check_obj(path);
  if (ext == ".ply") check_ply(path);
  if (ext == ".stl") check_stl(path);
  return 0;
}

}  // namespace countershade
