#pragma once
// countershade's own reader for the common OBJ files: vertices (x y z, with an optional w),
// texture coordinates, normals (counted, not kept) and polygons whose corners all have a texture
// coordinate or none has, with 1-based or negative indices; other statements (groups, objects,
// materials, smoothing groups) are skipped. The whole file is read at once and parsed in one pass
// with std::from_chars, far faster than the file check and OpenMesh's stream reader
// (docs/performance.md, "Mesh I/O").
//
// It declines, and the file check and OpenMesh read the file as before, for anything else: vertex
// colours, a face mixing corners with and without texture coordinates, and everything malformed
// (the check then names the line). Polygons are cut into fans from their first corner, each
// triangle corner with its own texture coordinate (OpenMesh set those of a polygon's last
// triangle only, and left the others undefined); texture coordinates no face uses are left out
// (OpenMesh gave every corner an undefined one).

#include <filesystem>
#include <optional>

#include "mesh/triangle_mesh.h"

namespace countershade {

// The file's positions, triangles and (when its faces have them) corner texture coordinates, or
// none where this reader does not vouch for reading the file as the file check and OpenMesh do.
std::optional<TriangleMesh> read_obj(const std::filesystem::path& path);

}  // namespace countershade
