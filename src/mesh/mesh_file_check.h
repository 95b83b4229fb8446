#pragma once
// Checks of a mesh file's structure before OpenMesh reads it. OpenMesh's readers trust their input:
// the OBJ reader skips what it cannot parse with only a warning, the PLY reader loops forever on a
// header without end_header, and element counts are allocated as given. These checks turn such
// files into an InputError with the file, the line and the problem.

#include <cstddef>
#include <filesystem>
#include <string>

namespace countershade {

// `ext` is the lower-case extension (".obj", ".ply", ".stl"; OFF has its own reader, off_reader.h).
// Returns the number of triangles an OBJ file describes after fan triangulation (0 for the other
// formats).
size_t check_mesh_file_structure(const std::filesystem::path& path, const std::string& ext);

}  // namespace countershade
