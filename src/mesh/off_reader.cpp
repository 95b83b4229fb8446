#include "mesh/off_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "mesh/mesh_text.h"

namespace countershade {
namespace {

// The next line of an OFF file that holds something (not blank, not a comment), split into words.
bool next_off_line(std::istream& in, std::vector<std::string>& w, size_t& number) {
  for (std::string line; std::getline(in, line);) {
    ++number;
    w = split_words(line.substr(0, line.find('#')));
    if (!w.empty()) return true;
  }
  return false;
}

// Every word of `w` from `first` on as a finite number.
std::vector<double> off_numbers(const std::vector<std::string>& w, size_t first,
                                const std::string& where) {
  std::vector<double> values;
  for (size_t k = first; k < w.size(); ++k) {
    double v = 0;
    if (!parse_number(w[k], v) || !std::isfinite(v))
      throw_input_error(where, "'" + w[k] + "' is not a finite number");
    values.push_back(v);
  }
  return values;
}

// The colour after a vertex's coordinates (and normal): three channels (a fourth, alpha, is
// ignored), as fractions in [0, 1] or as whole numbers 0..255 when any is above 1.
glm::vec3 off_colour(const std::vector<double>& values, size_t first, const std::string& where) {
  if (values.size() < first + 3)
    throw_input_error(where, "a COFF vertex needs a colour (three channels)");
  const double* c = values.data() + first;
  const bool bytes =
      std::all_of(c, c + 3, [](double v) { return v >= 0 && v <= 255 && v == std::floor(v); });
  const bool fractions = std::all_of(c, c + 3, [](double v) { return v >= 0 && v <= 1; });
  if (!bytes && !fractions)
    throw_input_error(where, "colour must be whole numbers 0..255 or fractions in [0, 1]");
  const float scale = fractions ? 1.0f : 1.0f / 255.0f;
  return {float(c[0]) * scale, float(c[1]) * scale, float(c[2]) * scale};
}

struct OffHeader {
  bool normals = false, colours = false;
  unsigned long long vertices = 0, faces = 0;
};

// "[ST][C][N]OFF" and the counts, on the same line or the next that holds something.
OffHeader read_off_header(std::istream& in, const std::string& file, size_t& number) {
  std::vector<std::string> w;
  const bool any = next_off_line(in, w, number);
  const std::string& magic = any ? w[0] : "";
  if (magic.size() < 3 || magic.compare(magic.size() - 3, 3, "OFF") != 0)
    throw_input_error(file, "not an OFF file (the first line does not start with OFF)");
  const std::string prefix = magic.substr(0, magic.size() - 3);
  if (prefix.find_first_not_of("STCN") != std::string::npos)
    throw_input_error(
        file, "OFF variant '" + magic + "' is not supported (use OFF, COFF, NOFF or STOFF)");
  if (std::find(w.begin(), w.end(), "BINARY") != w.end())
    throw_input_error(file, "binary OFF files are not supported (use ASCII OFF, PLY or OBJ)");
  OffHeader h;
  h.normals = prefix.find('N') != std::string::npos;
  h.colours = prefix.find('C') != std::string::npos;
  if (w.size() == 1 && !next_off_line(in, w, number)) w.clear();
  const size_t first = w.size() > 0 && w[0] == magic ? 1 : 0;
  if (w.size() < first + 2 || !parse_count(w[first], h.vertices) ||
      !parse_count(w[first + 1], h.faces))
    throw_input_error(file, "OFF header has no vertex and face counts");
  return h;
}

// One face line: "n i1 … in [colour]" with n ≥ 3 distinct indices below `vertices`.
std::vector<unsigned> off_face(const std::vector<std::string>& w, const std::string& where,
                               unsigned long long f, unsigned long long vertices) {
  const std::vector<double> values = off_numbers(w, 0, where);
  const double n = values[0];
  const std::string face_name = "face " + std::to_string(f);
  if (n < 3 || n != std::floor(n) || n + 1 > double(values.size()))
    throw_input_error(where, face_name + " must list at least 3 vertex indices after their count");
  std::vector<unsigned> face;
  for (size_t k = 1; k <= size_t(n); ++k) {
    if (values[k] < 0 || values[k] >= double(vertices) || values[k] != std::floor(values[k]))
      throw_input_error(where, face_name + " vertex index " + w[k] + " is out of range (0.." +
                                   std::to_string(vertices - 1) + ")");
    face.push_back(unsigned(values[k]));
  }
  std::vector<unsigned> sorted = face;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    throw_input_error(where, face_name + " is degenerate (a vertex appears twice)");
  return face;
}

}  // namespace

PolygonSoup read_off(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string file = path.string();
  size_t number = 0;
  const OffHeader h = read_off_header(in, file, number);
  const auto size = std::filesystem::file_size(path);
  if (h.vertices > size || h.faces > size)
    throw_input_error(file, "OFF header declares " + std::to_string(h.vertices) + " vertices and " +
                                std::to_string(h.faces) + " faces, more than a file of " +
                                std::to_string(size) + " bytes can hold");
  PolygonSoup soup;
  std::vector<std::string> w;
  for (unsigned long long v = 0; v < h.vertices; ++v) {
    if (!next_off_line(in, w, number))
      throw_input_error(file, "OFF file ends before vertex " + std::to_string(v));
    const std::string where = file + ": line " + std::to_string(number);
    const std::vector<double> values = off_numbers(w, 0, where);
    const size_t colour = 3 + (h.normals ? 3 : 0);
    if (values.size() < colour)
      throw_input_error(where, "vertex " + std::to_string(v) + " has too few values");
    soup.positions.emplace_back(values[0], values[1], values[2]);
    if (h.colours) soup.colours.push_back(off_colour(values, colour, where));
  }
  for (unsigned long long f = 0; f < h.faces; ++f) {
    if (!next_off_line(in, w, number))
      throw_input_error(file, "OFF file ends before face " + std::to_string(f));
    soup.add_face(off_face(w, file + ": line " + std::to_string(number), f, h.vertices));
  }
  return soup;
}

}  // namespace countershade
