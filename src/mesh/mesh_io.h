#pragma once
// Loading meshes (OBJ, PLY, OFF, STL), with validation. Polygons are triangulated. OFF and the
// common OBJ and PLY files are read by countershade's own readers and, when they are manifold
// surfaces, never reach OpenMesh; the rest is read or checked by OpenMesh.

#include <filesystem>
#include <optional>

#include "mesh/polygon_soup.h"
#include "mesh/triangle_mesh.h"

namespace countershade {

// Loads positions, faces, vertex colours and texture coordinates (per corner) when the file has
// them. Normals are left empty: the caller computes them with its crease angle.
// Throws InputError naming the file for: unreadable files, no faces, NaN/inf coordinates,
// face indices out of range, faces the reader had to drop (non-manifold), degenerate triangles.
// `soup`, when given, receives the vertices and polygons of an OFF or PLY file that countershade's
// own readers read (mesh/off_reader.h, mesh/ply_reader.h), so that a caller needing them as listed
// does not read the file again.
TriangleMesh load_mesh(const std::filesystem::path& path,
                       std::optional<PolygonSoup>* soup = nullptr);

// Checks a mesh in memory with the same rules; `where` prefixes the messages.
void validate_mesh(const TriangleMesh& mesh, const std::string& where);

}  // namespace countershade
