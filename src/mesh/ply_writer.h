#pragma once
// Writing a polygon soup as PLY: positions as floats, colours (when the soup has them) as bytes,
// faces as lists of int indices. The binary file is byte for byte what OpenMesh's writer gives for
// the same mesh, so files written before and after stay identical; the ASCII one gives each float
// in the fewest digits that read back to the same float. Both are written in large blocks from
// memory (docs/performance.md, "Mesh I/O").

#include <filesystem>

#include "mesh/polygon_soup.h"

namespace countershade {

enum class PlyEncoding { binary, ascii };

// Writes `soup` to `path` atomically (a temporary file renamed over it); throws std::runtime_error
// naming the file when it cannot.
void write_ply(const std::filesystem::path& path, const PolygonSoup& soup, PlyEncoding encoding);

}  // namespace countershade
