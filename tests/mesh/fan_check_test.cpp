// The fan check that lets load_mesh skip OpenMesh's half-edge build: it vouches for oriented
// manifold surfaces only, OpenMesh adds every face of each surface it vouches for in any order, and
// a file it vouches for loads as OpenMesh loaded it; what it does not vouch for still goes to
// OpenMesh (a bow tie loads, an edge of three faces is refused).

#include "mesh/fan_check.h"

#include <gtest/gtest.h>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>
#include <algorithm>
#include <random>
#include <sstream>
#include <vector>

#include "mesh/mesh_io.h"
#include "mesh/ply_writer.h"
#include "mesh/primitives.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;
using Triangles = std::vector<glm::uvec3>;

bool vouched(size_t vertices, const Triangles& triangles) {
  return forms_one_fan_at_every_vertex(vertices, triangles);
}

// Whether OpenMesh adds every triangle, in the given order, without a word on its error stream.
bool open_mesh_adds_all(size_t vertices, const Triangles& triangles) {
  std::ostringstream log;
  omerr().connect(log);
  OpenMesh::TriMesh_ArrayKernelT<> mesh;
  for (size_t v = 0; v < vertices; ++v) mesh.add_vertex({0, 0, 0});
  for (const glm::uvec3& t : triangles)
    mesh.add_face(mesh.vertex_handle(int(t.x)), mesh.vertex_handle(int(t.y)),
                  mesh.vertex_handle(int(t.z)));
  omerr().disconnect(log);
  return mesh.n_faces() == triangles.size() && log.str().empty();
}

TEST(FanCheck, VouchesForSurfacesOnly) {
  EXPECT_TRUE(vouched(3, {{0, 1, 2}}));
  EXPECT_TRUE(vouched(5, {{0, 1, 2}}));  // vertices without faces
  const Triangles tetrahedron = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  EXPECT_TRUE(vouched(4, tetrahedron));
  Triangles flipped = tetrahedron;
  std::swap(flipped[3].x, flipped[3].y);
  EXPECT_FALSE(vouched(4, flipped)) << "a face against its neighbours' orientation";
  EXPECT_FALSE(vouched(5, {{0, 1, 2}, {0, 3, 4}})) << "a bow tie: two fans at vertex 0";
  const Triangles fin = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  EXPECT_FALSE(vouched(5, fin)) << "an edge of three faces";
  EXPECT_FALSE(open_mesh_adds_all(5, fin));
  EXPECT_FALSE(vouched(3, {{0, 1, 1}})) << "a repeated corner";
  EXPECT_FALSE(vouched(3, {{0, 1, 3}})) << "an index out of range";
  // Two tetrahedra sharing vertex 0: two closed fans there.
  const Triangles twins = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3},
                           {0, 5, 4}, {0, 4, 6}, {4, 5, 6}, {5, 0, 6}};
  EXPECT_TRUE(vouched(4, Triangles(twins.begin(), twins.begin() + 4)));
  EXPECT_FALSE(vouched(7, twins));

  // Vertices of many triangles (checked by sorting rather than scanning): a disc's centre, closed
  // and open, and two such fans meeting at one vertex.
  auto fan = [](unsigned centre, unsigned first_rim, unsigned count, bool closed) {
    Triangles t;
    for (unsigned k = 0; k + (closed ? 0 : 1) < count; ++k)
      t.push_back({centre, first_rim + k, first_rim + (k + 1) % count});
    return t;
  };
  EXPECT_TRUE(vouched(41, fan(0, 1, 40, true)));
  EXPECT_TRUE(vouched(41, fan(0, 1, 40, false)));
  Triangles two = fan(0, 1, 20, false);
  for (const glm::uvec3& t : fan(0, 21, 20, false)) two.push_back(t);
  EXPECT_FALSE(vouched(41, two));
  Triangles repeated = fan(0, 1, 40, true);
  repeated.push_back({0, 5, 6});
  EXPECT_FALSE(vouched(41, repeated));
}

TEST(FanCheck, OpenMeshAddsEveryFaceOfAVouchedSurfaceInAnyOrder) {
  const std::pair<const char*, TriangleMesh> surfaces[] = {
      {"grid", make_plane(2.0, 12)},
      {"bunny", load_mesh(testing::mesh_path("stanford-bunny.obj"))},
      {"spot", load_mesh(testing::mesh_path("spot.obj"))},
      {"fandisk", load_mesh(testing::mesh_path("fandisk.obj"))}};
  std::mt19937 random(7);
  for (const auto& [name, mesh] : surfaces) {
    ASSERT_TRUE(vouched(mesh.vertex_count(), mesh.triangles)) << name;
    for (int order = 0; order < 6; ++order) {
      Triangles shuffled = mesh.triangles;
      std::shuffle(shuffled.begin(), shuffled.end(), random);
      for (glm::uvec3& t : shuffled)  // the same triangle from another corner
        for (int turn = int(random() % 3); turn > 0; --turn) t = {t.y, t.z, t.x};
      EXPECT_TRUE(vouched(mesh.vertex_count(), shuffled)) << name << ", order " << order;
      EXPECT_TRUE(open_mesh_adds_all(mesh.vertex_count(), shuffled)) << name << ", order " << order;
    }
  }
}

PolygonSoup soup_of(const std::vector<glm::vec3>& positions, const Triangles& triangles) {
  PolygonSoup soup;
  soup.positions = positions;
  for (const glm::uvec3& t : triangles) soup.add_face(std::vector<unsigned>{t.x, t.y, t.z});
  return soup;
}

TEST(FanCheck, WhatItDoesNotVouchForStillGoesToOpenMesh) {
  testing::TempDir dir;
  const std::vector<glm::vec3> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
  const fs::path bow_tie = dir / "bow-tie.ply";
  write_ply(bow_tie, soup_of(points, {{0, 1, 2}, {0, 3, 4}}), PlyEncoding::ascii);
  EXPECT_EQ(load_mesh(bow_tie).triangles, (Triangles{{0, 1, 2}, {0, 3, 4}}));
  const std::vector<glm::vec3> fin = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
  const fs::path three = dir / "three-faces.ply";
  write_ply(three, soup_of(fin, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}), PlyEncoding::binary);
  const std::string message = testing::input_error_of([&] { load_mesh(three); });
  EXPECT_NE(message.find("three-faces.ply: mesh is non-manifold"), std::string::npos) << message;
}

}  // namespace
}  // namespace countershade
