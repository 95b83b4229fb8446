#pragma once
// What every fuzz harness shares: the input as a file (most readers take a path, as the commands
// do), and the rule that decides a finding. Bad input must end in an InputError (exit 2, one line);
// any other exception would reach the user as "failure" with exit 1, so the harness aborts on it
// and libFuzzer records the input. Crashes, hangs, leaks and sanitizer reports are findings too.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"

namespace countershade::fuzz {

// This process's own folder under the temp dir, where inputs and the files they may refer to lie.
inline const std::filesystem::path& input_folder() {
  static const std::filesystem::path folder = [] {
    auto f = std::filesystem::temp_directory_path() /
             ("countershade-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(f);
    return f;
  }();
  return folder;
}

// The input bytes written to a file `name` in the input folder.
inline std::filesystem::path write_input(const uint8_t* data, size_t size,
                                         const std::string& name) {
  const std::filesystem::path path = input_folder() / name;
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path;
}

// A file the inputs may refer to by a relative path (a scene's mesh, an experiment's scene), so
// that the fuzzer gets past "no such file".
inline void write_support_file(const std::string& name, const std::string& text) {
  std::ofstream(input_folder() / name, std::ios::binary | std::ios::trunc) << text;
}

// A valid scene of primitives, for the experiment inputs to refer to as "scene.json".
inline const char* const kSupportScene = R"({
  "version": 1,
  "camera": {"eye": [0, 1, 4], "target": [0, 0, 0], "fov": 40, "width": 16, "height": 12},
  "render": {"spp": 1},
  "objects": [{"shape": {"type": "sphere", "radius": 1, "subdivisions": 1}}],
  "lights": [{"type": "directional", "direction": [1, 2, 1], "irradiance": 2}]
})";

// A tetrahedron with texture coordinates, for the scene inputs to refer to as "mesh.obj".
inline const char* const kSupportMesh =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\n"
    "f 1/1 3/3 2/2\nf 1/1 2/2 4/3\nf 1/1 4/3 3/3\nf 2/2 3/3 4/1\n";

// Runs `read` on one input: an InputError is the expected answer to bad input; anything else is
// a finding.
template <typename Read>
int expect_clean_refusal(Read&& read) {
  try {
    read();
  } catch (const InputError&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "finding: an exception other than InputError: %s\n", e.what());
    std::abort();
  }
  return 0;
}

}  // namespace countershade::fuzz
