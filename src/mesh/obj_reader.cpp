#include "mesh/obj_reader.h"

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

#include "core/mapped_file.h"

namespace countershade {
namespace {

using Words = std::vector<std::string_view>;

bool separates(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// The line's words, split at spaces, tabs and carriage returns; false where it holds a vertical
// tab or a form feed, which the file check and OpenMesh treat in ways of their own.
bool split(std::string_view line, Words& words) {
  words.clear();
  for (size_t i = 0; i < line.size();) {
    if (line[i] == '\v' || line[i] == '\f') return false;
    if (separates(line[i])) {
      ++i;
      continue;
    }
    const size_t start = i;
    while (i < line.size() && !separates(line[i]) && line[i] != '\v' && line[i] != '\f') ++i;
    words.push_back(line.substr(start, i - start));
  }
  return true;
}

// A word that is wholly a finite number within float's range.
bool finite_float(std::string_view word, float& value) {
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  return error == std::errc() && end == word.data() + word.size() && std::abs(value) <= 1e38f;
}

// An index field: a whole non-zero integer, resolved (1-based, negative from the end) against the
// `defined` items so far into a 0-based index; false when it is none of those or out of range.
bool resolve(std::string_view field, long long defined, long long& index) {
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), index);
  if (error != std::errc() || end != field.data() + field.size() || index == 0) return false;
  index = index < 0 ? defined + index : index - 1;
  return index >= 0 && index < defined;
}

struct ObjReader {
  TriangleMesh mesh;
  std::vector<glm::vec2> uvs;
  long long normals = 0;
  size_t corners_with_uv = 0, corners_without_uv = 0;
  std::vector<long long> face_vertices, face_uvs;

  // One statement; false where the reader declines the file.
  bool statement(const Words& w) {
    if (w.empty() || w[0][0] == '#') return true;
    if (w[0] == "v") return vertex(w);
    if (w[0] == "vt") return texture_coordinate(w);
    if (w[0] == "vn") return ++normals, true;
    if (w[0] == "f") return face(w);
    return true;  // groups, objects, materials: nothing load_mesh keeps
  }

  bool vertex(const Words& w) {
    // Six numbers or more would be a colour, which OpenMesh reads.
    if (w.size() < 4 || w.size() > 6) return false;
    float value[5];
    for (size_t k = 1; k < w.size(); ++k)
      if (!finite_float(w[k], value[k - 1])) return false;
    mesh.positions.emplace_back(value[0], value[1], value[2]);
    return true;
  }

  bool texture_coordinate(const Words& w) {
    float value[3];
    if (w.size() < 3 || w.size() > 4) return false;
    for (size_t k = 1; k < w.size(); ++k)
      if (!finite_float(w[k], value[k - 1])) return false;
    uvs.emplace_back(value[0], value[1]);
    return true;
  }

  // "v", "v/vt", "v/vt/vn" or "v//vn", each index valid at this point of the file.
  bool corner(std::string_view c) {
    const size_t first = c.find('/');
    const size_t second = first == std::string_view::npos ? first : c.find('/', first + 1);
    if (second != std::string_view::npos && c.find('/', second + 1) != std::string_view::npos)
      return false;
    long long vertex = 0, uv = -1, normal = 0;
    if (!resolve(c.substr(0, first), (long long)mesh.positions.size(), vertex)) return false;
    const std::string_view uv_field = first == std::string_view::npos
                                          ? std::string_view()
                                          : c.substr(first + 1, second - first - 1);
    if (!uv_field.empty() && !resolve(uv_field, (long long)uvs.size(), uv)) return false;
    if (second != std::string_view::npos && second + 1 < c.size() &&
        !resolve(c.substr(second + 1), normals, normal))
      return false;
    face_vertices.push_back(vertex);
    face_uvs.push_back(uv);
    (uv_field.empty() ? corners_without_uv : corners_with_uv) += 1;
    return true;
  }

  bool face(const Words& w) {
    face_vertices.clear();
    face_uvs.clear();
    for (size_t k = 1; k < w.size(); ++k)
      if (!corner(w[k])) return false;
    const size_t n = face_vertices.size();
    if (n < 3) return false;
    // A face whose corners do not all have a texture coordinate, or all lack one (found by the
    // fuzzer: the corners without one were read at index −1).
    for (long long uv : face_uvs)
      if ((uv >= 0) != (face_uvs[0] >= 0)) return false;
    for (size_t i = 0; i < n; ++i)
      for (size_t j = i + 1; j < n; ++j)
        if (face_vertices[i] == face_vertices[j]) return false;
    for (size_t k = 1; k + 1 < n; ++k) {
      mesh.triangles.emplace_back(face_vertices[0], face_vertices[k], face_vertices[k + 1]);
      if (face_uvs[0] < 0) continue;
      for (size_t i : {size_t(0), k, k + 1}) mesh.corner_uvs.push_back(uvs[size_t(face_uvs[i])]);
    }
    return true;
  }
};

}  // namespace

std::optional<TriangleMesh> read_obj(const std::filesystem::path& path) {
  const MappedFile file(path);
  const std::string_view bytes = file.bytes();
  ObjReader reader;
  // Room for as many vertices and triangles as the shortest lines ("v 0 0 0", "f 1 2 3") would
  // give: pages never written are never touched, and growing by copies was a tenth of the read.
  reader.mesh.positions.reserve(bytes.size() / 8);
  reader.mesh.triangles.reserve(bytes.size() / 8);
  Words words;
  for (size_t at = 0; at < bytes.size();) {
    size_t end = bytes.find('\n', at);
    if (end == std::string::npos) end = bytes.size();
    if (!split(bytes.substr(at, end - at), words) || !reader.statement(words)) return std::nullopt;
    at = end + 1;
  }
  if (reader.corners_with_uv > 0 && reader.corners_without_uv > 0) return std::nullopt;
  return std::move(reader.mesh);
}

}  // namespace countershade
