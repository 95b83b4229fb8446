#include "enhance/multiscale_normals.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <glm/geometric.hpp>
#include <mutex>

#include "core/parallel.h"
#include "mesh/smoothing.h"
#include "render/shading.h"

namespace countershade {
namespace {

// Area-weighted normals of the welded points (so seams and hard edges get one normal).
std::vector<glm::dvec3> point_normals(const Object& object) {
  const SurfaceGraph& surface = object.surface;
  std::vector<glm::dvec3> normals(surface.point_count(), glm::dvec3(0.0));
  const auto& p = object.mesh.positions;
  for (const glm::uvec3& t : object.mesh.triangles) {
    const glm::dvec3 area2 = glm::cross(glm::dvec3(p[t.y] - p[t.x]), glm::dvec3(p[t.z] - p[t.x]));
    for (int c = 0; c < 3; ++c) normals[surface.point_of[t[c]]] += area2;
  }
  for (glm::dvec3& n : normals) n = glm::length(n) > 0 ? glm::normalize(n) : glm::dvec3(0, 0, 1);
  return normals;
}

// `steps[c]` further Jacobi steps for the points of component c: each point takes the
// normalised sum of its 1-ring (itself excluded), as 3D unsharp masking's smoothing does.
void smooth_normals(const SurfaceGraph& surface, const std::vector<int>& steps,
                    std::vector<glm::dvec3>& normals, int threads) {
  const int most = steps.empty() ? 0 : *std::max_element(steps.begin(), steps.end());
  std::vector<glm::dvec3> next(normals.size());
  for (int step = 0; step < most; ++step) {
    parallel_ranges(
        normals.size(), threads,
        [&](size_t begin, size_t end) {
          for (size_t point = begin; point < end; ++point) {
            next[point] = normals[point];
            if (step >= steps[surface.components.label[point]]) continue;
            glm::dvec3 sum(0.0);
            for (uint32_t q : surface.adjacency.of(point)) sum += normals[q];
            if (glm::length(sum) > 1e-12) next[point] = glm::normalize(sum);
          }
        },
        1024);
    normals.swap(next);
  }
}

std::vector<glm::vec3> to_vertices(const SurfaceGraph& surface,
                                   const std::vector<glm::dvec3>& per_point) {
  std::vector<glm::vec3> out(surface.point_of.size());
  for (size_t v = 0; v < out.size(); ++v) out[v] = glm::vec3(per_point[surface.point_of[v]]);
  return out;
}

}  // namespace

MultiscaleNormals::MultiscaleNormals(std::shared_ptr<const Scene> shared_scene, double sigma1,
                                     int scales, int threads)
    : scene_(std::move(shared_scene)),
      sigma1_(sigma1),
      scales_(scales),
      vertex_normals_(scene_->objects.size()),
      iterations_(scene_->objects.size()) {
  const Scene& scene = *scene_;
  require_surface_graphs(scene, "multiscale normals");
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const Object& object = scene.objects[o];
    const SurfaceGraph& surface = object.surface;
    const std::vector<double>& edge = surface.mean_edge_length;
    std::vector<glm::dvec3> normals = point_normals(object);
    std::vector<int> done(edge.size(), 0);
    for (int k = 2; k <= scales; ++k) {
      const double sigma = sigma1 * std::pow(kNormalScaleRatio, k - 2);
      std::vector<int> target(edge.size()), more(edge.size());
      for (size_t c = 0; c < edge.size(); ++c) {
        target[c] = iterations_for_sigma(sigma, edge[c]);
        more[c] = std::max(
            0, target[c] - done[c]);  // σ² grows with the steps: continue from the finer scale
      }
      smooth_normals(surface, more, normals, threads);
      done = target;
      vertex_normals_[o].push_back(to_vertices(surface, normals));
      iterations_[o].push_back(target);
    }
  }
}

bool MultiscaleNormals::same_input(const Scene& scene, double sigma1, int scales) const {
  if (sigma1 != sigma1_ || scales != scales_ || scene.objects.size() != scene_->objects.size())
    return false;
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const TriangleMesh &a = scene.objects[o].mesh, &b = scene_->objects[o].mesh;
    if (a.positions != b.positions || a.triangles != b.triangles) return false;
  }
  return true;
}

std::shared_ptr<const MultiscaleNormals> MultiscaleNormals::shared(
    std::shared_ptr<const Scene> scene, double sigma1, int scales, int threads) {
  constexpr size_t kKept = 2;  // a few MB each for a large scan; the sets's scenes come in order
  static std::mutex mutex;
  static std::deque<std::shared_ptr<const MultiscaleNormals>> recent;
  {
    std::lock_guard<std::mutex> lock(mutex);
    for (const auto& normals : recent)
      if (normals->same_input(*scene, sigma1, scales)) return normals;
  }
  auto made = std::make_shared<const MultiscaleNormals>(std::move(scene), sigma1, scales, threads);
  std::lock_guard<std::mutex> lock(mutex);
  recent.push_front(made);
  if (recent.size() > kKept) recent.pop_back();
  return made;
}

glm::dvec3 MultiscaleNormals::at(const SurfacePoint& point, int k) const {
  const auto& normals = vertex_normals_[point.object][size_t(k - 2)];
  const glm::uvec3 t = scene_->objects[point.object].mesh.triangles[point.triangle];
  const glm::dvec3 n = (1 - point.b1 - point.b2) * glm::dvec3(normals[t.x]) +
                       point.b1 * glm::dvec3(normals[t.y]) + point.b2 * glm::dvec3(normals[t.z]);
  const double length = glm::length(n);
  return length > 1e-12 ? n / length : point.shading_normal;
}

void MultiscaleNormals::at_shading_point(const ShadingInputs& s, glm::dvec3* n) const {
  const double side = glm::dot(s.normal, s.point.shading_normal) < 0 ? -1.0 : 1.0;
  n[0] = s.normal;
  for (int k = 2; k <= scales_; ++k) n[k - 1] = side * at(s.point, k);
}

nlohmann::json MultiscaleNormals::describe() const {
  nlohmann::json iterations = nlohmann::json::array();
  for (size_t o = 0; o < iterations_.size(); ++o)
    for (int k = 2; k <= scales_; ++k) iterations.push_back(iterations_[o][size_t(k - 2)]);
  return {{"mode", "surface"}, {"smoothing_iterations", iterations}};
}

}  // namespace countershade
