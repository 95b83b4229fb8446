#pragma once
// Helpers shared by the test suites: temporary folders, small files, running the CLI.

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/isa.h"

namespace countershade::testing {

// Runs `check` with the AVX-512 functions and again without them (the path of other processors),
// so that one machine tests both; once where the processor has no AVX-512.
inline void with_and_without_avx512(const std::function<void()>& check) {
  check();
  if (!has_avx512()) return;
  allow_avx512(false);
  struct Restore {
    ~Restore() { allow_avx512(true); }
  } restore;
  check();
}

inline std::filesystem::path source_dir() { return COUNTERSHADE_SOURCE_DIR; }
// The repository's meshes (data/meshes) and the tests' reference results (tests/reference).
inline std::filesystem::path mesh_path(const std::string& name) {
  return source_dir() / "data/meshes" / name;
}
inline std::filesystem::path reference_path(const std::string& relative) {
  return source_dir() / "tests/reference" / relative;
}

// A fresh folder under the system temp dir, removed with its contents at scope exit.
class TempDir {
 public:
  TempDir() {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("countershade-test-" + std::to_string(::getpid()) + "-" + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

// A small scene for stimulus-set tests: a lit cube and a ball, two samples per pixel.
inline constexpr const char* kLitCubeScene = R"({
  "version": 1,
  "camera": {"eye": [3, 2.2, 4], "target": [0, 0, 0], "fov": 32, "width": 640, "height": 480},
  "render": {"spp": 2},
  "display": {"background": 0.18},
  "objects": [{"name": "cube", "shape": {"type": "box", "size": [1.5, 1.5, 1.5], "subdivisions": 16}, "material": {"albedo": 0.5}},
              {"name": "ball", "shape": {"type": "sphere", "radius": 0.4, "subdivisions": 3}, "transform": {"translate": [1.3, 0, 0.6]}}],
  "lights": [{"type": "directional", "direction": [0.35, -1, 0.6], "irradiance": 1.6}, {"type": "ambient", "radiance": 0.25}]
})";

// A box on a ground plane; the camera orbits while the box slides: 4 frames at 4 fps.
inline constexpr const char* kOrbitingBoxScene = R"({"version": 1,
  "camera": {"eye": [0, 1.2, 4], "target": [0, 0.3, 0], "fov": 35, "width": 64, "height": 48},
  "render": {"spp": 2, "seed": 7},
  "objects": [{"name": "ground", "shape": {"type": "plane", "size": 6, "subdivisions": 24}, "material": {"albedo": 0.6}},
              {"name": "box", "shape": {"type": "box", "size": [0.6, 0.6, 0.6], "subdivisions": 6},
               "transform": {"translate": [0, 0.3, 0]}}],
  "lights": [{"type": "directional", "direction": [0.4, 1, 0.3], "irradiance": 2.5}, {"type": "ambient", "radiance": 0.2}],
  "animation": {"duration": 1, "fps": 4,
    "camera": {"eye": {"times": [0, 1], "values": [[0, 1.2, 4], [1.2, 1.2, 3.8]]}},
    "objects": [{"name": "box", "translate": {"times": [0, 1], "values": [[0, 0, 0], [0.4, 0, 0]]}}]}
})";

inline std::filesystem::path write_file(const std::filesystem::path& path,
                                        const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  return path;
}

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Runs `program` with `arguments` (already shell-quoted).
inline CommandResult run_program(const std::string& program, const std::string& arguments) {
  std::string command = program + " " + arguments + " 2>&1";
  CommandResult result;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    result.output.append(buffer.data(), n);
  int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

// Runs the countershade binary with `arguments` (already shell-quoted).
inline CommandResult run_cli(const std::string& arguments) {
  return run_program(COUNTERSHADE_BINARY, arguments);
}

// The message of the InputError that `f` throws, or "(no error)".
inline std::string input_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const countershade::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// One fenced code block of a Markdown document: its language (```json: "json"), the line number
// of its first line, and its lines.
struct CodeBlock {
  std::string language;
  int first_line = 0;
  std::vector<std::string> lines;
};

// The fenced code blocks of a Markdown file, indented ones (in lists) included.
inline std::vector<CodeBlock> markdown_code_blocks(const std::filesystem::path& path) {
  std::istringstream in(read_file(path));
  std::vector<CodeBlock> blocks;
  bool inside = false;
  int number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    const size_t start = line.find_first_not_of(' ');
    if (start != std::string::npos && line.compare(start, 3, "```") == 0) {
      inside = !inside;
      if (inside) blocks.push_back({line.substr(start + 3), number + 1, {}});
    } else if (inside) {
      blocks.back().lines.push_back(line);
    }
  }
  return blocks;
}

inline int count_lines(const std::string& text) {
  int lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

}  // namespace countershade::testing
