#include "mesh/triangle_mesh.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/trigonometric.hpp>

namespace countershade {

void BoundingBox::extend(const glm::vec3& p) {
  lo = glm::min(lo, p);
  hi = glm::max(hi, p);
}

void BoundingBox::extend(const BoundingBox& b) {
  if (!b.valid()) return;
  extend(b.lo);
  extend(b.hi);
}

float BoundingBox::diagonal() const { return valid() ? glm::length(hi - lo) : 0.0f; }

BoundingBox bounding_box(const TriangleMesh& mesh) {
  BoundingBox box;
  for (const auto& p : mesh.positions) box.extend(p);
  return box;
}

double triangle_double_area(const TriangleMesh& mesh, size_t t) {
  const auto& tri = mesh.triangles[t];
  glm::dvec3 a = mesh.positions[tri.x], b = mesh.positions[tri.y], c = mesh.positions[tri.z];
  return glm::length(glm::cross(b - a, c - a));
}

double mean_edge_length(const TriangleMesh& mesh) {
  double sum = 0.0;
  for (const auto& tri : mesh.triangles)
    for (int c = 0; c < 3; ++c)
      sum += glm::length(glm::dvec3(mesh.positions[tri[c]]) -
                         glm::dvec3(mesh.positions[tri[(c + 1) % 3]]));
  return mesh.triangles.empty() ? 0.0 : sum / (3.0 * double(mesh.triangles.size()));
}

void compute_corner_normals(TriangleMesh& mesh, double crease_angle_deg) {
  const size_t nf = mesh.triangles.size(), nv = mesh.positions.size();
  std::vector<glm::dvec3> face_normal(nf);
  std::vector<double> corner_angle(3 * nf);
  for (size_t t = 0; t < nf; ++t) {
    const auto& tri = mesh.triangles[t];
    glm::dvec3 p[3] = {mesh.positions[tri.x], mesh.positions[tri.y], mesh.positions[tri.z]};
    glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
    double len = glm::length(n);
    face_normal[t] = len > 0 ? n / len : glm::dvec3(0.0);
    for (int c = 0; c < 3; ++c) {
      glm::dvec3 e1 = p[(c + 1) % 3] - p[c], e2 = p[(c + 2) % 3] - p[c];
      double l1 = glm::length(e1), l2 = glm::length(e2);
      corner_angle[3 * t + c] =
          (l1 > 0 && l2 > 0) ? std::acos(std::clamp(glm::dot(e1, e2) / (l1 * l2), -1.0, 1.0)) : 0.0;
    }
  }

  const auto [offsets, corners] = vertex_corners(mesh);

  const double cos_crease =
      crease_angle_deg >= 180.0 ? -2.0 : std::cos(glm::radians(crease_angle_deg));
  mesh.corner_normals.assign(3 * nf, glm::vec3(0.0f));
  for (size_t v = 0; v < nv; ++v) {
    for (uint32_t i = offsets[v]; i < offsets[v + 1]; ++i) {
      uint32_t corner = corners[i];
      const glm::dvec3& own = face_normal[corner / 3];
      glm::dvec3 sum(0.0);
      for (uint32_t j = offsets[v]; j < offsets[v + 1]; ++j) {
        uint32_t other = corners[j];
        const glm::dvec3& n = face_normal[other / 3];
        if (glm::dot(own, n) >= cos_crease) sum += corner_angle[other] * n;
      }
      double len = glm::length(sum);
      mesh.corner_normals[corner] = glm::vec3(len > 0 ? sum / len : own);
    }
  }
}

VertexCorners vertex_corners(const TriangleMesh& mesh) {
  const size_t nv = mesh.vertex_count(), nf = mesh.triangle_count();
  VertexCorners out;
  out.offsets.assign(nv + 1, 0);
  out.corners.resize(3 * nf);
  for (const auto& tri : mesh.triangles)
    for (int c = 0; c < 3; ++c) ++out.offsets[tri[c] + 1];
  for (size_t v = 0; v < nv; ++v) out.offsets[v + 1] += out.offsets[v];
  std::vector<uint32_t> fill(out.offsets.begin(), out.offsets.end() - 1);
  for (size_t t = 0; t < nf; ++t)
    for (int c = 0; c < 3; ++c) out.corners[fill[mesh.triangles[t][c]]++] = uint32_t(3 * t + c);
  return out;
}

void transform_mesh(TriangleMesh& mesh, const glm::dmat4& transform) {
  for (auto& p : mesh.positions) p = glm::vec3(transform * glm::dvec4(glm::dvec3(p), 1.0));
  glm::dmat3 normal_matrix = glm::transpose(glm::inverse(glm::dmat3(transform)));
  for (auto& n : mesh.corner_normals) n = glm::vec3(glm::normalize(normal_matrix * glm::dvec3(n)));
  // A mirroring transform flips the winding; restore counter-clockwise fronts.
  if (glm::determinant(glm::dmat3(transform)) < 0.0) {
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      std::swap(mesh.triangles[t].y, mesh.triangles[t].z);
      std::swap(mesh.corner_normals[3 * t + 1], mesh.corner_normals[3 * t + 2]);
      if (mesh.has_uvs()) std::swap(mesh.corner_uvs[3 * t + 1], mesh.corner_uvs[3 * t + 2]);
    }
  }
}

}  // namespace countershade
