#pragma once
// Error messages quote what they found in the user's files, and those may hold anything: a
// newline would break the promise of one line on stderr, a stray binary byte would garble the
// terminal. one_line() keeps printable ASCII and well-formed UTF-8 (σ, λ, file names) and writes
// every other byte as \xNN.

#include <string>
#include <string_view>

namespace countershade {

std::string one_line(std::string_view text);

}  // namespace countershade
