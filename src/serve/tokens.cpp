#include "serve/tokens.h"

#include <sys/random.h>

#include <array>
#include <stdexcept>

#include "core/sha256.h"

namespace countershade::serve {

std::string random_token() {
  std::array<unsigned char, 16> bytes;
  size_t got = 0;
  while (got < bytes.size()) {
    const ssize_t n = ::getrandom(bytes.data() + got, bytes.size() - got, 0);
    if (n < 0) throw std::runtime_error("the kernel gave no random bytes");
    got += size_t(n);
  }
  static const char* const kHex = "0123456789abcdef";
  std::string token;
  for (unsigned char b : bytes) token += {kHex[b >> 4], kHex[b & 15]};
  return token;
}

bool is_token(const std::string& text) {
  return text.size() == 32 && text.find_first_not_of("0123456789abcdef") == std::string::npos;
}

std::string token_hash(const std::string& token) { return sha256_hex(token); }

}  // namespace countershade::serve
