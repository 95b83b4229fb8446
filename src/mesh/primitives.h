#pragma once
// Procedural primitives as welded triangle meshes with uniform-ish tessellation (surface smoothing
// needs connected, evenly sized triangles). All are centred at the origin; normals are left empty.

#include "mesh/triangle_mesh.h"

namespace countershade {

// Square in the xz-plane (normal +y), side `size`, `subdivisions` quads per side. UVs in [0,1]².
TriangleMesh make_plane(double size, int subdivisions);

// The plane above displaced along +y by a procedural height field with coarse and fine relief:
// y = coarse·relief_coarse(u, v) + fine·relief_fine(u, v), u = x/size + 0.5, v = z/size + 0.5.
// The triangles are the flat plane's, so its tessellation stays even.
TriangleMesh make_relief(double size, int subdivisions, double coarse, double fine);

// The two parts of the relief's height field over the unit square, both smooth and of height
// about 1: six broad hills and valleys (Gaussians of σ = 0.14), and fine ridges of wavelength 1/14,
// circles around (u, v) = (−0.35, 1.25), whose orientation turns across the square.
double relief_coarse(double u, double v);
double relief_fine(double u, double v);

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

// How make_cylinder and make_disc grid a round shape of `segments` around (at least 3): side rows
// and cap rings about one segment wide. In double, so that a caller can check the size first.
struct RoundGrid {
  int segments;
  double rows, rings;
  // At most this many triangles: the side's rows and both caps (or one cap for a disc), each ring
  // of the caps counted as a full row.
  double triangle_bound(bool disc) const {
    return 2.0 * segments * (disc ? rings : 2.0 * rings + rows);
  }
};
RoundGrid round_grid(double radius, double height, int segments);

// Flat disc in the xz-plane facing +y, `segments` around and concentric rings of about the
// segment width: a cylinder's cap on its own. An open surface, so that a decal (a die's pip, a
// painted mark) has no hidden side whose light would enter its 3D unsharp masking signal.
TriangleMesh make_disc(double radius, int segments);

}  // namespace countershade
