#pragma once
// countershade's own reader for ASCII OFF files. OpenMesh's OFF reader reads tokens without
// checking them: a malformed face line made it loop, and colours above 1 reached an unchecked
// float-to-byte conversion (both found by the fuzzer). This one reads line by line and refuses
// anything it does not understand, naming the line.
//
// Accepted: [ST][C][N]OFF, then the vertex, face (and edge) counts on the same line or the next;
// '#' comments; one vertex per line (x y z, then nx ny nz with N, then r g b [a] with C, as
// fractions or as bytes 0..255); one face per line (n i1 … in with n ≥ 3, 0-based indices, an
// optional colour that is ignored). Binary OFF and the 4OFF and nOFF variants are refused.

#include <filesystem>

#include "mesh/polygon_soup.h"

namespace countershade {

PolygonSoup read_off(const std::filesystem::path& path);

}  // namespace countershade
