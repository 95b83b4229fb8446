#pragma once
// A PLY file checked before OpenMesh reads it: OpenMesh loops forever or crashes on some malformed
// headers and ASCII bodies (found by fuzzing), so those are refused first with a clear line.

#include <filesystem>

namespace countershade {

// How much of a file to check: the header (and whether the body can hold what it declares), or
// also an ASCII body's every value. countershade's PLY reader parses every value itself, so the
// body's check is for the files it leaves to OpenMesh.
enum class PlyCheck { header, header_and_body };

// The header (its first line "ply", a known format, vertex and face elements whose counts the
// file can hold, known property types, end_header within 1 MB) and, for ASCII files, the body:
// every element has all its values, each wholly a number (an integer for integer types).
// InputError naming the file and the line or element otherwise.
void check_ply(const std::filesystem::path& path, PlyCheck check = PlyCheck::header_and_body);

}  // namespace countershade
