#include "core/one_line.h"

#include <cstdint>
#include <cstdio>

#include "core/utf8.h"

namespace countershade {

std::string one_line(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size();) {
    const uint8_t c = uint8_t(text[i]);
    const size_t sequence = c >= 0x80 ? utf8_sequence(text, i) : 0;
    if (sequence > 0) {
      out.append(text.substr(i, sequence));
      i += sequence;
      continue;
    }
    if (c >= 0x20 && c < 0x7F) {
      out += char(c);
    } else {
      char escaped[5];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", unsigned(c));
      out += escaped;
    }
    ++i;
  }
  return out;
}

}  // namespace countershade
