#include "procedures/procedure.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#ifndef __EMSCRIPTEN__
#include <unistd.h>
#endif

#include "core/error.h"
#include "core/number_format.h"

namespace countershade::procedures {

size_t Grid::nearest(double lambda) const {
  const size_t hi =
      size_t(std::lower_bound(lambdas.begin(), lambdas.end(), lambda) - lambdas.begin());
  if (hi == 0) return 0;
  if (hi == lambdas.size()) return hi - 1;
  return lambda - lambdas[hi - 1] <= lambdas[hi] - lambda ? hi - 1 : hi;
}

size_t Grid::point_of(double lambda, const std::string& where) const {
  const size_t i = nearest(lambda);
  if (std::abs(lambdas[i] - lambda) > 1e-9)
    throw_input_error(where, "λ " + format_value(lambda) + " is not on the set's λ grid (" +
                                 format_value(lambdas.front()) + " to " +
                                 format_value(lambdas.back()) + ")");
  return i;
}

double procedure_memory_limit() {
#ifdef __EMSCRIPTEN__
  return kWebAssemblyMemoryBytes / 2;
#else
  return double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE)) / 2;
#endif
}

std::string exact_number(double v) {
  char buffer[64];
#ifdef __EMSCRIPTEN__
  // emscripten's libc++ has no floating-point to_chars: the fewest %g digits that read back as v
  // (the browser writes no replay CSV; this only keeps the function whole there).
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
    if (std::strtod(buffer, nullptr) == v) break;
  }
  return buffer;
#else
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
#endif
}

}  // namespace countershade::procedures
