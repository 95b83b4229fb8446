#pragma once
// Tessellation refinement: uniform Laplacian smoothing spreads a signal by the local edge length,
// so meshes with long edges are split until no edge exceeds a target length.

#include <vector>

#include "mesh/triangle_mesh.h"

namespace countershade {

// Splits the longest edge at its midpoint, repeatedly, until every edge is at most `max_length`.
// Each split cuts both triangles beside the edge in two (the mesh stays conforming and welded).
// Corner attributes (normals, UVs) are interpolated per triangle, so creases and UV seams stay
// intact; vertex colours and `vertex_values` (one per vertex, e.g. importance weights) are
// interpolated along the edge. Returns the number of splits.
size_t refine_long_edges(TriangleMesh& mesh, double max_length,
                         std::vector<float>* vertex_values = nullptr);

}  // namespace countershade
