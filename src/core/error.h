#pragma once
// Error kinds that decide the exit status: bad input (2) versus everything else (1).

#include <stdexcept>
#include <string>

namespace countershade {

// Bad input or usage. The message is one line: "<file>: <key path or field>: <what is wrong>".
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Builds "where: what", skipping an empty `where`.
[[noreturn]] inline void throw_input_error(const std::string& where, const std::string& what) {
  throw InputError(where.empty() ? what : where + ": " + what);
}

}  // namespace countershade
