#pragma once
// A coloured mesh kept exactly as read (vertex order, positions, polygon faces), so a tool can
// change its vertex colours and write it back without touching anything else.

#include <filesystem>
#include <glm/vec3.hpp>
#include <memory>
#include <utility>
#include <vector>

#include "mesh/ply_writer.h"

namespace countershade {

class ColoredMeshFile {
 public:
  // Reads a PLY/OFF/OBJ mesh with per-vertex colours (as load_mesh does; OBJ through OpenMesh).
  // Throws InputError naming the file when it cannot be read, is invalid (see load_mesh) or has no
  // vertex colours.
  static ColoredMeshFile read(const std::filesystem::path& path);
  ~ColoredMeshFile();
  ColoredMeshFile(ColoredMeshFile&&) noexcept;

  size_t vertex_count() const;
  std::vector<glm::vec3> positions() const;
  // The vertices and faces as stored (the colours as their bytes' values).
  const PolygonSoup& polygons() const;
  // Colours as stored, in [0,1] (8-bit per channel in the file).
  std::vector<glm::dvec3> colors() const;
  void set_colors(const std::vector<glm::dvec3>& colors);

  // Writes a PLY with the same vertices and faces and the current colours (mesh/ply_writer.h). The
  // file appears atomically (temporary file, then rename).
  void write(const std::filesystem::path& path, PlyEncoding encoding = PlyEncoding::binary) const;

 private:
  struct Impl;
  explicit ColoredMeshFile(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace countershade
