#pragma once
// Whether a triangle list is an oriented manifold surface (with or without boundary), found on the
// flat triangles. load_mesh uses it to skip building OpenMesh's half-edge connectivity, which it
// needs only to find the faces OpenMesh cannot add: on a surface where every vertex's triangles
// form one fan, OpenMesh adds every face in any order.

#include <cstddef>
#include <glm/vec3.hpp>
#include <span>

namespace countershade {

// True when every triangle has three distinct corners below `vertex_count`, no directed edge
// belongs to two triangles, and the triangles around each vertex form a single fan: one chain of
// neighbours, open (a boundary vertex) or closed (an inner one). False says only that the check
// cannot vouch for the mesh (a bow tie, an edge of three faces, a flipped face): OpenMesh then
// decides, as it always has.
bool forms_one_fan_at_every_vertex(size_t vertex_count, std::span<const glm::uvec3> triangles);

}  // namespace countershade
