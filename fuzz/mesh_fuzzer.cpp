// Fuzzes mesh loading (mesh/mesh_io, through OpenMesh): the first byte picks the format (OBJ,
// PLY, OFF or STL), the rest is the file.
#include "fuzz/fuzz_input.h"
#include "mesh/mesh_io.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  static const char* const kNames[] = {"mesh.obj", "mesh.ply", "mesh.off", "mesh.stl"};
  const auto path = countershade::fuzz::write_input(data + 1, size - 1, kNames[data[0] % 4]);
  return countershade::fuzz::expect_clean_refusal([&] { countershade::load_mesh(path); });
}
