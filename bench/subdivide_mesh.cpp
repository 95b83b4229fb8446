// Makes a large coloured mesh for the smoothing measurements: every triangle of the input cut
// into K² (bench/subdivided_mesh.h), each vertex coloured by a pattern of its position, so that
// smoothing has a signal at every scale.
// Not a benchmark; run by hand:
//   build/bin/subdivide_mesh data/meshes/igea.obj 9 /tmp/igea-10m.ply     # 10.9 M vertices
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <glm/geometric.hpp>
#include <glm/gtc/type_precision.hpp>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "mesh/mesh_io.h"
#include "subdivided_mesh.h"

namespace {

using countershade::TriangleMesh;
using countershade::bench::Subdivided;

// Stripes at three scales of the mesh's size, so the smoothing has structure to remove.
glm::u8vec3 pattern(const glm::vec3& p, float size) {
  const auto wave = [&](float scale, float phase) {
    return 0.5f + 0.5f * std::sin(p.x * scale / size + phase);
  };
  const float v = 0.5f * wave(40, 0) + 0.3f * wave(170, 1) +
                  0.2f * std::sin(p.y * 900 / size) * std::sin(p.z * 700 / size);
  const float c = std::clamp(40.0f + 180.0f * v, 0.0f, 255.0f);
  return {uint8_t(c), uint8_t(0.8f * c + 20), uint8_t(0.6f * c + 40)};
}

void write_ply(const Subdivided& mesh, float size, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  out << "ply\nformat binary_little_endian 1.0\nelement vertex " << mesh.positions.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty "
         "uchar green\n"
         "property uchar blue\nelement face "
      << mesh.triangles.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const glm::vec3& p : mesh.positions) {
    const glm::u8vec3 c = pattern(p, size);
    out.write(reinterpret_cast<const char*>(&p), sizeof p);
    out.write(reinterpret_cast<const char*>(&c), sizeof c);
  }
  for (const glm::uvec3& t : mesh.triangles) {
    const uint8_t three = 3;
    out.write(reinterpret_cast<const char*>(&three), 1);
    out.write(reinterpret_cast<const char*>(&t), sizeof t);
  }
  if (!out) throw std::runtime_error("could not write " + path);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4 || std::stoi(argv[2]) < 1) {
    std::cerr << "usage: subdivide_mesh INPUT K OUTPUT.ply   (each triangle into K² triangles)\n";
    return 2;
  }
  const int k = std::stoi(argv[2]);
  const TriangleMesh in = countershade::load_mesh(argv[1]);
  const Subdivided out = countershade::bench::subdivide(in, k);
  const countershade::BoundingBox box = countershade::bounding_box(in);
  write_ply(out, box.diagonal(), argv[3]);
  std::printf("%s: %zu vertices, %zu triangles\n", argv[3], out.positions.size(),
              out.triangles.size());
  return 0;
}
