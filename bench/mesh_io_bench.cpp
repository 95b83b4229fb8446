// Reading and writing meshes: countershade's readers and writer (mesh/ply_reader.h,
// mesh/obj_reader.h, mesh/ply_writer.h) against OpenMesh's, on one core, for a coloured grid of
// 1,000,000 vertices and 1,996,002 triangles as PLY in ASCII (about 88 MB) and binary (about
// 39 MB) and as OBJ (about 61 MB, no colours); and the whole of load_mesh, which also checks the
// file and that it is a surface. Bytes per second are the file's.
//   build/bin/countershade_bench --benchmark_filter="PlyRead|PlyWrite|ObjRead"

#include <benchmark/benchmark.h>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "mesh/mesh_io.h"
#include "mesh/open_mesh_soup.h"
#include "mesh/ply_reader.h"
#include "mesh/ply_writer.h"

namespace countershade {
namespace {

constexpr int kSide = 1000;  // vertices per side of the grid

// The grid as a PLY file in the given format, written once per process.
std::filesystem::path grid_ply(bool binary) {
  const auto path =
      std::filesystem::temp_directory_path() /
      (std::string("countershade-bench-grid-") + (binary ? "binary" : "ascii") + ".ply");
  if (std::filesystem::exists(path)) return path;
  std::ofstream out(path, std::ios::binary);
  const int vertices = kSide * kSide, faces = 2 * (kSide - 1) * (kSide - 1);
  out << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\nelement vertex "
      << vertices << "\nproperty float x\nproperty float y\nproperty float z\n"
      << "property uchar red\nproperty uchar green\nproperty uchar blue\nelement face " << faces
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      const float p[3] = {x * 0.001f, y * 0.001f, 0.05f * float((x * 7 + y * 3) % 11) * 0.01f};
      const unsigned char c[3] = {uint8_t(x % 256), uint8_t(y % 256), uint8_t((x + y) % 256)};
      if (binary) {
        out.write(reinterpret_cast<const char*>(p), sizeof p);
        out.write(reinterpret_cast<const char*>(c), sizeof c);
      } else {
        char line[96];
        std::snprintf(line, sizeof line, "%.9g %.9g %.9g %d %d %d\n", p[0], p[1], p[2], c[0], c[1],
                      c[2]);
        out << line;
      }
    }
  for (int y = 0; y + 1 < kSide; ++y)
    for (int x = 0; x + 1 < kSide; ++x) {
      const int v = y * kSide + x;
      const int tris[2][3] = {{v, v + 1, v + kSide + 1}, {v, v + kSide + 1, v + kSide}};
      for (const auto& t : tris)
        if (binary) {
          const unsigned char n = 3;
          out.write(reinterpret_cast<const char*>(&n), 1);
          out.write(reinterpret_cast<const char*>(t), sizeof t);
        } else {
          out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
        }
    }
  return path;
}

void BM_PlyReadCountershade(benchmark::State& state) {
  const auto path = grid_ply(state.range(0) == 1);
  for (auto _ : state) benchmark::DoNotOptimize(read_ply_soup(path));
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(std::filesystem::file_size(path)));
  state.SetLabel(state.range(0) == 1 ? "binary" : "ascii");
}
BENCHMARK(BM_PlyReadCountershade)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_PlyReadOpenMesh(benchmark::State& state) {
  const auto path = grid_ply(state.range(0) == 1);
  for (auto _ : state) {
    OpenMesh::TriMesh_ArrayKernelT<> mesh;
    mesh.request_vertex_colors();
    OpenMesh::IO::Options options = OpenMesh::IO::Options::VertexColor;
    benchmark::DoNotOptimize(OpenMesh::IO::read_mesh(mesh, path.string(), options));
  }
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(std::filesystem::file_size(path)));
  state.SetLabel(state.range(0) == 1 ? "binary" : "ascii");
}
BENCHMARK(BM_PlyReadOpenMesh)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_PlyReadLoadMesh(benchmark::State& state) {
  const auto path = grid_ply(state.range(0) == 1);
  for (auto _ : state) benchmark::DoNotOptimize(load_mesh(path));
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(std::filesystem::file_size(path)));
  state.SetLabel(state.range(0) == 1 ? "binary" : "ascii");
}
BENCHMARK(BM_PlyReadLoadMesh)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// The grid's soup, read once per process.
const PolygonSoup& grid_soup() {
  static const PolygonSoup soup = *read_ply_soup(grid_ply(true));
  return soup;
}

std::filesystem::path written_path(bool binary) {
  return std::filesystem::temp_directory_path() /
         (std::string("countershade-bench-written-") + (binary ? "binary" : "ascii") + ".ply");
}

void BM_PlyWriteCountershade(benchmark::State& state) {
  const bool binary = state.range(0) == 1;
  const auto path = written_path(binary);
  for (auto _ : state)
    write_ply(path, grid_soup(), binary ? PlyEncoding::binary : PlyEncoding::ascii);
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(std::filesystem::file_size(path)));
  state.SetLabel(binary ? "binary" : "ascii");
  std::filesystem::remove(path);
}
BENCHMARK(BM_PlyWriteCountershade)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_PlyWriteOpenMesh(benchmark::State& state) {
  const bool binary = state.range(0) == 1;
  const auto path = written_path(binary);
  OpenMesh::TriMesh_ArrayKernelT<> mesh;
  mesh.request_vertex_colors();
  add_soup_to_open_mesh(grid_soup(), mesh);
  OpenMesh::IO::Options options = OpenMesh::IO::Options::VertexColor;
  if (binary) options += OpenMesh::IO::Options::Binary;
  for (auto _ : state)
    benchmark::DoNotOptimize(OpenMesh::IO::write_mesh(mesh, path.string(), options));
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(std::filesystem::file_size(path)));
  state.SetLabel(binary ? "binary" : "ascii");
  std::filesystem::remove(path);
}
BENCHMARK(BM_PlyWriteOpenMesh)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// The grid as an OBJ file (positions only, triangles), written once per process.
std::filesystem::path grid_obj() {
  const auto path = std::filesystem::temp_directory_path() / "countershade-bench-grid.obj";
  if (std::filesystem::exists(path)) return path;
  const PolygonSoup& soup = grid_soup();
  std::ofstream out(path, std::ios::binary);
  char line[96];
  for (const glm::vec3& p : soup.positions) {
    std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x, p.y, p.z);
    out << line;
  }
  for (size_t f = 0; f < soup.face_count(); ++f) {
    const auto face = soup.face(f);
    out << "f " << face[0] + 1 << ' ' << face[1] + 1 << ' ' << face[2] + 1 << '\n';
  }
  return path;
}

void BM_ObjReadLoadMesh(benchmark::State& state) {
  const auto path = grid_obj();
  for (auto _ : state) benchmark::DoNotOptimize(load_mesh(path));
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(std::filesystem::file_size(path)));
}
BENCHMARK(BM_ObjReadLoadMesh)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_ObjReadOpenMesh(benchmark::State& state) {
  const auto path = grid_obj();
  for (auto _ : state) {
    OpenMesh::TriMesh_ArrayKernelT<> mesh;
    benchmark::DoNotOptimize(OpenMesh::IO::read_mesh(mesh, path.string()));
  }
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(std::filesystem::file_size(path)));
}
BENCHMARK(BM_ObjReadOpenMesh)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace countershade
