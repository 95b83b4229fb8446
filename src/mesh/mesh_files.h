#pragma once
// The mesh files a scene names, loaded on all cores at once (each file once) before its objects are
// read in order: reading meshes is most of a scene's load, and one object's file need not wait for
// the one before it.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "mesh/triangle_mesh.h"

namespace countershade {

class MeshFiles {
 public:
  MeshFiles() = default;
  // Loads every file of `paths` with load_mesh, in parallel; a file named twice is read once. A
  // file that cannot be loaded keeps its InputError for take().
  explicit MeshFiles(const std::vector<std::filesystem::path>& paths);

  // The mesh of `path`, or its InputError thrown again. Each call gets a mesh of its own (the last
  // call for a file takes the loaded one, the others a copy); a path not given above is loaded now.
  TriangleMesh take(const std::filesystem::path& path);

 private:
  struct Loaded {
    TriangleMesh mesh;
    std::string error;  // the InputError's message, when loading failed
    int takes_left = 0;
  };
  std::map<std::filesystem::path, Loaded> files_;
};

}  // namespace countershade
