#pragma once
// countershade's own reader for the common PLY files: vertices with positions (and 8-bit colours,
// normals or an alpha, which it skips or keeps) and faces as one list of vertex indices, in ASCII
// or binary. The whole file is read at once and parsed in one pass (std::from_chars, or the bytes
// themselves), faster than OpenMesh's stream reader, six times so on binary files
// (docs/performance.md, "Mesh I/O"). It declines, and OpenMesh
// reads the file as before, when the file has anything else (texture coordinates, float colours,
// other properties or elements). The file's structure is checked first (mesh_file_check.h).

#include <filesystem>
#include <optional>

#include "mesh/polygon_soup.h"

namespace countershade {

// The file's vertices, colours and polygons, or none where it holds more than this reader reads.
// Throws InputError naming the file and the face for a vertex index out of range, a face of fewer
// than three vertices, or a value it cannot parse.
std::optional<PolygonSoup> read_ply_soup(const std::filesystem::path& path);

}  // namespace countershade
