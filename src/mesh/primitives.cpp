#include "mesh/primitives.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <numbers>
#include <tuple>

namespace countershade {
namespace {

// Welds vertices by an integer key so shared lattice points become one vertex.
template <class Key>
class Welder {
 public:
  explicit Welder(TriangleMesh& mesh) : mesh_(mesh) {}
  unsigned vertex(const Key& key, const glm::vec3& position) {
    auto [it, inserted] = ids_.try_emplace(key, unsigned(mesh_.positions.size()));
    if (inserted) mesh_.positions.push_back(position);
    return it->second;
  }

 private:
  TriangleMesh& mesh_;
  std::map<Key, unsigned> ids_;
};

// Adds the two triangles of quad (a, b, c, d) in counter-clockwise order, split along the
// shorter diagonal to keep triangles well shaped.
void add_quad(TriangleMesh& mesh, unsigned a, unsigned b, unsigned c, unsigned d) {
  float ac = glm::length(mesh.positions[a] - mesh.positions[c]);
  float bd = glm::length(mesh.positions[b] - mesh.positions[d]);
  if (ac <= bd) {
    mesh.triangles.push_back({a, b, c});
    mesh.triangles.push_back({a, c, d});
  } else {
    mesh.triangles.push_back({a, b, d});
    mesh.triangles.push_back({b, c, d});
  }
}

// Grid coordinates along one box axis from -h to h: `edge` rows in each cut-back band of width
// r at the ends, and interior rows of about the target spacing.
std::vector<double> axis_coordinates(double h, double r, int edge, double spacing) {
  std::vector<double> xs;
  double inner = h - r;
  int interior = std::max(1, int(std::lround(2.0 * inner / spacing)));
  if (r > 0)
    for (int i = 0; i < edge; ++i) xs.push_back(-h + r * i / edge);
  for (int i = 0; i <= interior; ++i) xs.push_back(-inner + 2.0 * inner * i / interior);
  if (r > 0)
    for (int i = 1; i <= edge; ++i) xs.push_back(inner + r * i / edge);
  return xs;
}

}  // namespace

TriangleMesh make_plane(double size, int subdivisions) {
  TriangleMesh mesh;
  int n = std::max(1, subdivisions);
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      mesh.positions.emplace_back(size * (double(i) / n - 0.5), 0.0, size * (double(j) / n - 0.5));
  auto id = [n](int i, int j) { return unsigned(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      // Counter-clockwise seen from +y: (i,j) -> (i,j+1) -> (i+1,j+1) -> (i+1,j).
      size_t first = mesh.triangles.size();
      add_quad(mesh, id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j));
      for (size_t t = first; t < mesh.triangles.size(); ++t)
        for (int c = 0; c < 3; ++c) {
          const auto& p = mesh.positions[mesh.triangles[t][c]];
          mesh.corner_uvs.emplace_back(p.x / size + 0.5, 0.5 - p.z / size);
        }
    }
  return mesh;
}

namespace {

double gaussian_bump(double u, double v, double cu, double cv, double sigma) {
  return std::exp(-((u - cu) * (u - cu) + (v - cv) * (v - cv)) / (2.0 * sigma * sigma));
}

}  // namespace

double relief_coarse(double u, double v) {
  // {u, v, amplitude}: hills (+) and valleys (−) of σ = 0.14.
  static constexpr double kHills[6][3] = {{0.25, 0.30, 1.0}, {0.70, 0.25, -0.7},
                                          {0.55, 0.60, 0.8}, {0.20, 0.75, -0.6},
                                          {0.80, 0.75, 0.9}, {0.45, 0.95, 0.5}};
  double h = 0;
  for (const auto& [cu, cv, a] : kHills) h += a * gaussian_bump(u, v, cu, cv, 0.14);
  return h;
}

double relief_fine(double u, double v) {
  // Ridges concentric around a point outside the square: they never cross, and their orientation
  // turns by about 55° across it.
  constexpr double kCentreU = -0.35, kCentreV = 1.25, kWavelength = 1.0 / 14.0;
  return std::sin(2.0 * std::numbers::pi * std::hypot(u - kCentreU, v - kCentreV) / kWavelength);
}

TriangleMesh make_relief(double size, int subdivisions, double coarse, double fine) {
  TriangleMesh mesh = make_plane(size, subdivisions);
  for (glm::vec3& p : mesh.positions) {
    const double u = double(p.x) / size + 0.5, v = double(p.z) / size + 0.5;
    p.y = float(coarse * relief_coarse(u, v) + fine * relief_fine(u, v));
  }
  return mesh;
}

namespace {

// The lattice of a box with rounded or bevelled edges: coordinates per axis, and where a lattice
// point lands on the surface (the cut-back bands projected onto the edge profile).
struct BoxLattice {
  glm::dvec3 h, inner;
  double r = 0;
  EdgeProfile profile = EdgeProfile::sharp;
  std::vector<double> axes[3];

  glm::vec3 place(const glm::dvec3& p) const {
    const glm::dvec3 q = glm::clamp(p, -inner, inner);
    const glm::dvec3 d = p - q;
    if (r <= 0 || (d.x == 0 && d.y == 0 && d.z == 0)) return glm::vec3(p);
    if (profile == EdgeProfile::bevel) return glm::vec3(q + r * glm::normalize(d));
    const double l1 = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
    return glm::vec3(q + d * (r / l1));
  }
};

// One face of the box: axis `a` fixed at its first (side 0) or last lattice index, walking the
// other two axes u and v; corner uvs span the face.
void add_box_face(TriangleMesh& mesh, Welder<std::tuple<int, int, int>>& welder,
                  const BoxLattice& box, int a, int side) {
  const int u = (a + 1) % 3, v = (a + 2) % 3;
  const int fixed = side == 0 ? 0 : int(box.axes[a].size()) - 1;
  const int nu = int(box.axes[u].size()), nv = int(box.axes[v].size());
  auto vertex = [&](int i, int j) {
    int idx[3];
    idx[a] = fixed;
    idx[u] = i;
    idx[v] = j;
    const glm::dvec3 p(box.axes[0][idx[0]], box.axes[1][idx[1]], box.axes[2][idx[2]]);
    return welder.vertex({idx[0], idx[1], idx[2]}, box.place(p));
  };
  const glm::dvec3& h = box.h;
  for (int j = 0; j + 1 < nv; ++j)
    for (int i = 0; i + 1 < nu; ++i) {
      const unsigned a0 = vertex(i, j), a1 = vertex(i + 1, j), a2 = vertex(i + 1, j + 1),
                     a3 = vertex(i, j + 1);
      const size_t first = mesh.triangles.size();
      // (u, v, a) is right-handed, so u->v is counter-clockwise seen from +a.
      if (side == 1)
        add_quad(mesh, a0, a1, a2, a3);
      else
        add_quad(mesh, a0, a3, a2, a1);
      for (size_t t = first; t < mesh.triangles.size(); ++t)
        for (int c = 0; c < 3; ++c) {
          const auto& p = mesh.positions[mesh.triangles[t][c]];
          mesh.corner_uvs.emplace_back((p[u] + h[u]) / (2 * h[u]), (p[v] + h[v]) / (2 * h[v]));
        }
    }
}

}  // namespace

TriangleMesh make_box(const glm::dvec3& size, EdgeProfile profile, double radius, int edge_segments,
                      int subdivisions) {
  BoxLattice box;
  box.h = size * 0.5;
  box.profile = profile;
  box.r = profile == EdgeProfile::sharp
              ? 0.0
              : std::min(radius, 0.999 * std::min({box.h.x, box.h.y, box.h.z}));
  const int edge = std::max(1, edge_segments);
  const double spacing =
      2.0 * (std::max({box.h.x, box.h.y, box.h.z}) - box.r) / std::max(1, subdivisions);
  for (int a = 0; a < 3; ++a) box.axes[a] = axis_coordinates(box.h[a], box.r, edge, spacing);
  box.inner = box.h - glm::dvec3(box.r);
  TriangleMesh mesh;
  Welder<std::tuple<int, int, int>> welder(mesh);
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) add_box_face(mesh, welder, box, a, side);
  return mesh;
}

TriangleMesh make_sphere(double radius, int subdivisions) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<glm::dvec3> verts = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                   {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                   {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<glm::uvec3> faces = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                   {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                   {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                   {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& v : verts) v = glm::normalize(v);
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<unsigned, unsigned>, unsigned> midpoint;
    auto mid = [&](unsigned a, unsigned b) {
      auto key = std::minmax(a, b);
      auto [it, inserted] = midpoint.try_emplace(key, unsigned(verts.size()));
      if (inserted) verts.push_back(glm::normalize(verts[a] + verts[b]));
      return it->second;
    };
    std::vector<glm::uvec3> next;
    for (const auto& f : faces) {
      unsigned ab = mid(f.x, f.y), bc = mid(f.y, f.z), ca = mid(f.z, f.x);
      next.insert(next.end(), {{f.x, ab, ca}, {f.y, bc, ab}, {f.z, ca, bc}, {ab, bc, ca}});
    }
    faces.swap(next);
  }
  TriangleMesh mesh;
  for (const auto& v : verts) mesh.positions.emplace_back(v * radius);
  mesh.triangles = faces;
  return mesh;
}

namespace {

double turn_angle(int i, int n) { return 2.0 * std::numbers::pi * (i % n) / n; }

// A cylinder's cap at height y: concentric rings inwards from the side's outer ring `outer`, then a
// centre vertex; facing down for cap 0, up for cap 1.
void add_cylinder_cap(TriangleMesh& mesh, std::vector<unsigned> outer, double radius, int rings,
                      double y, int cap) {
  const int n = int(outer.size());
  for (int k = rings - 1; k > 0; --k) {
    std::vector<unsigned> ring(n);
    for (int i = 0; i < n; ++i) {
      ring[i] = unsigned(mesh.positions.size());
      const double rr = radius * k / rings;
      mesh.positions.emplace_back(rr * std::cos(turn_angle(i, n)), y,
                                  -rr * std::sin(turn_angle(i, n)));
    }
    for (int i = 0; i < n; ++i) {
      if (cap == 1)
        add_quad(mesh, outer[i], outer[(i + 1) % n], ring[(i + 1) % n], ring[i]);
      else
        add_quad(mesh, outer[(i + 1) % n], outer[i], ring[i], ring[(i + 1) % n]);
    }
    outer = ring;
  }
  const unsigned centre = unsigned(mesh.positions.size());
  mesh.positions.emplace_back(0.0, y, 0.0);
  for (int i = 0; i < n; ++i) {
    if (cap == 1)
      mesh.triangles.push_back({outer[i], outer[(i + 1) % n], centre});
    else
      mesh.triangles.push_back({outer[(i + 1) % n], outer[i], centre});
  }
}

}  // namespace

RoundGrid round_grid(double radius, double height, int segments) {
  const int n = std::max(3, segments);
  const double width = 2.0 * std::numbers::pi * radius / n;
  return {n, std::max(1.0, std::round(height / width)), std::max(1.0, std::round(radius / width))};
}

TriangleMesh make_cylinder(double radius, double height, int segments) {
  TriangleMesh mesh;
  const RoundGrid grid = round_grid(radius, height, segments);
  const int n = grid.segments, rows = int(grid.rows), rings = int(grid.rings);
  // Side grid: rows+1 rings of n vertices.
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i < n; ++i)
      mesh.positions.emplace_back(radius * std::cos(turn_angle(i, n)),
                                  -height / 2 + height * j / rows,
                                  -radius * std::sin(turn_angle(i, n)));
  auto side = [n](int i, int j) { return unsigned(j * n + (i % n)); };
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < n; ++i)
      add_quad(mesh, side(i, j), side(i + 1, j), side(i + 1, j + 1), side(i, j + 1));
  // Caps share the side's outer rings.
  for (int cap = 0; cap < 2; ++cap) {
    std::vector<unsigned> outer(n);
    for (int i = 0; i < n; ++i) outer[i] = side(i, cap == 0 ? 0 : rows);
    add_cylinder_cap(mesh, outer, radius, rings, cap == 0 ? -height / 2 : height / 2, cap);
  }
  return mesh;
}

TriangleMesh make_disc(double radius, int segments) {
  TriangleMesh mesh;
  const RoundGrid grid = round_grid(radius, 0.0, segments);
  const int n = grid.segments;
  std::vector<unsigned> outer(n);
  for (int i = 0; i < n; ++i) {
    outer[i] = unsigned(mesh.positions.size());
    mesh.positions.emplace_back(radius * std::cos(turn_angle(i, n)), 0.0,
                                -radius * std::sin(turn_angle(i, n)));
  }
  add_cylinder_cap(mesh, outer, radius, int(grid.rings), 0.0, 1);
  return mesh;
}

}  // namespace countershade
