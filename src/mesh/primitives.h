#pragma once
// Procedural primitives as welded triangle meshes with uniform-ish tessellation (surface smoothing
// needs connected, evenly sized triangles). All are centred at the origin; normals are left empty.

#include "mesh/triangle_mesh.h"

namespace countershade {

// Square in the xz-plane (normal +y), side `size`, `subdivisions` quads per side. UVs in [0,1]².
TriangleMesh make_plane(double size, int subdivisions);

enum class EdgeProfile { sharp, bevel, chamfer };

// Axis-aligned box with extents `size`. With a bevel (rounded) or chamfer (flat 45°) profile,
// edges are cut back by `radius` using `edge_segments` rows. `subdivisions` rows span the
// longest flat side; the other sides get rows in proportion. UVs per face in [0,1]².
TriangleMesh make_box(const glm::dvec3& size, EdgeProfile profile, double radius, int edge_segments,
                      int subdivisions);

// Geodesic (icosahedral) sphere: 20·4^subdivisions triangles of near-equal size.
TriangleMesh make_sphere(double radius, int subdivisions);

// Capped cylinder along y, height `height`, `segments` around, rows along the side matched to
// the segment width, and concentric rings on the caps.
TriangleMesh make_cylinder(double radius, double height, int segments);

}  // namespace countershade
