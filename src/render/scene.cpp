#include "render/scene.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>
#include <string>

#include "core/error.h"
#include "core/number_format.h"
#include "core/parallel.h"
#include "mesh/refine.h"

namespace countershade {
namespace fs = std::filesystem;

BoundingBox Scene::bounds() const {
  BoundingBox box;
  for (const auto& o : objects) box.extend(bounding_box(o.mesh));
  return box;
}

namespace {

SurfaceGraph surface_of(const TriangleMesh& mesh) {
  return surface_graph(mesh.positions, mesh.triangles);
}

}  // namespace

void build_surface_graphs(Scene& scene, int threads) {
  parallel_ranges(scene.objects.size(), threads, [&](size_t begin, size_t end) {
    for (size_t o = begin; o < end; ++o)
      scene.objects[o].surface = surface_of(scene.objects[o].mesh);
  });
}

void require_surface_graphs(const Scene& scene, const char* who) {
  for (const Object& object : scene.objects)
    if (object.surface.point_of.size() != object.mesh.vertex_count())
      throw std::logic_error(std::string(who) +
                             ": the scene was loaded without its surface graphs");
}

namespace {

// About how many triangles splitting every edge to max_edge_length makes: a triangle whose
// longest edge is k lengths long becomes about k² triangles.
double refined_triangle_estimate(const Scene& scene, double max_edge_length) {
  double total = 0;
  for (const auto& object : scene.objects)
    for (const auto& t : object.mesh.triangles) {
      const auto& p = object.mesh.positions;
      const double longest = std::max({glm::distance(p[t.x], p[t.y]), glm::distance(p[t.y], p[t.z]),
                                       glm::distance(p[t.z], p[t.x])});
      const double k = std::max(1.0, std::ceil(longest / max_edge_length));
      total += k * k;
    }
  return total;
}

}  // namespace

size_t refine_scene(Scene& scene, double max_edge_length) {
  constexpr double kMaxTriangles = 5e7;  // about 10 GB of mesh, vertex signal and smoothing
  const double estimate = refined_triangle_estimate(scene, max_edge_length);
  if (!(estimate <= kMaxTriangles))
    throw InputError("--refine " + format_value(max_edge_length) +
                     ": splitting edges to that length would make about " +
                     format_value(double(std::llround(estimate))) +
                     " triangles; the limit is 50000000 (choose a longer length)");
  size_t splits = 0;
  for (auto& object : scene.objects)
    splits += refine_long_edges(object.mesh, max_edge_length, &object.importance);
  build_surface_graphs(scene);
  return splits;
}

}  // namespace countershade
