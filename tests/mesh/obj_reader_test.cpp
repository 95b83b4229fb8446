// countershade's OBJ reader against OpenMesh's, its reference: the same positions, triangles and
// texture coordinates on the repository's meshes; each triangle of a polygon with its own corners'
// texture coordinates (OpenMesh's were undefined); and the files it declines (colours, mixed
// corners, anything malformed), which load_mesh leaves to the file check and OpenMesh as before.

#include "mesh/obj_reader.h"

#include <gtest/gtest.h>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <string>
#include <vector>

#include "mesh/mesh_io.h"
#include "test_util.h"

namespace countershade {
namespace {

namespace fs = std::filesystem;

// What OpenMesh reads of a file: positions, triangles and each corner's texture coordinate.
TriangleMesh as_open_mesh_reads_it(const fs::path& path) {
  OpenMesh::TriMesh_ArrayKernelT<> om;
  om.request_halfedge_texcoords2D();
  OpenMesh::IO::Options options = OpenMesh::IO::Options::FaceTexCoord;
  EXPECT_TRUE(OpenMesh::IO::read_mesh(om, path.string(), options));
  TriangleMesh mesh;
  for (auto vh : om.vertices()) {
    const auto p = om.point(vh);
    mesh.positions.emplace_back(p[0], p[1], p[2]);
  }
  for (auto fh : om.faces()) {
    glm::uvec3 t;
    int k = 0;
    for (auto heh : om.fh_range(fh)) {
      t[k++] = unsigned(om.to_vertex_handle(heh).idx());
      if (options.check(OpenMesh::IO::Options::FaceTexCoord))
        mesh.corner_uvs.emplace_back(om.texcoord2D(heh)[0], om.texcoord2D(heh)[1]);
    }
    mesh.triangles.push_back(t);
  }
  return mesh;
}

TEST(ObjReader, ReadsWhatOpenMeshReadsOnTheSharedMeshes) {
  for (const char* name : {"stanford-bunny.obj", "spot.obj", "fandisk.obj", "igea.obj"}) {
    const fs::path path = testing::mesh_path(name);
    const auto ours = read_obj(path);
    ASSERT_TRUE(ours) << name << ": declined";
    const TriangleMesh reference = as_open_mesh_reads_it(path);
    EXPECT_EQ(ours->positions, reference.positions) << name;
    EXPECT_EQ(ours->triangles, reference.triangles) << name;
    EXPECT_EQ(ours->corner_uvs, reference.corner_uvs) << name;
    EXPECT_EQ(ours->has_uvs(), std::string(name) == "spot.obj") << name;
  }
}

TEST(ObjReader, GivesEachTriangleOfAPolygonItsCornersTextureCoordinates) {
  testing::TempDir dir;
  const fs::path quad = testing::write_file(
      dir / "quad.obj",
      "# a quad\r\nmtllib none.mtl\no square\nv 0 0 0\nv 1 0 0\nv 1 1 0 1\nv 0 1 0\n"
      "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1 0\nvn 0 0 1\ng top\ns off\nf 1/1/1 2/2/1 -2/-2/-1 4/4/\n");
  const auto mesh = read_obj(quad);
  ASSERT_TRUE(mesh);
  EXPECT_EQ(mesh->triangles, (std::vector<glm::uvec3>{{0, 1, 2}, {0, 2, 3}}));
  const std::vector<glm::vec2> uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
  EXPECT_EQ(mesh->corner_uvs, uvs);
  EXPECT_EQ(load_mesh(quad).corner_uvs, uvs);
}

TEST(ObjReader, DeclinesWhatItDoesNotReadAsTheCheckAndOpenMeshWould) {
  testing::TempDir dir;
  const std::string square = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  const std::pair<const char*, std::string> declined[] = {
      {"colours", "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n"},
      {"mixed corners", square + "vt 0 0\nf 1/1 2/1 3/1\nf 1 3 4\n"},
      {"mixed corners in a face", square + "vt 0 0\nvt 1 0\nf 1/1 2/ 3/2\n"},
      {"not a number", square + "v 1 x 0\nf 1 2 3\n"},
      {"not finite", square + "v 1 nan 0\nf 1 2 3\n"},
      {"index zero", square + "f 0 1 2\n"},
      {"index out of range", square + "f 1 2 5\n"},
      {"texture coordinate out of range", square + "f 1/1 2/1 3/1\n"},
      {"repeated vertex", square + "f 1 2 2\n"},
      {"two corners", square + "f 1 2\n"},
      {"vertical tab", square + "f 1 2 3\n\vv 0 0 1\n"},
      {"four fields", square + "f 1/1/1/1 2 3\n"}};
  for (const auto& [what, text] : declined)
    EXPECT_FALSE(read_obj(testing::write_file(dir / "declined.obj", text))) << what;
  // A coloured file still loads with its colours, through OpenMesh.
  const TriangleMesh coloured =
      load_mesh(testing::write_file(dir / "colours.obj", declined[0].second));
  ASSERT_TRUE(coloured.has_vertex_colors());
  EXPECT_EQ(coloured.vertex_colors[1], glm::vec3(0, 1, 0));
}

}  // namespace
}  // namespace countershade
