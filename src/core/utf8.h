#pragma once
// Well-formed UTF-8 (RFC 3629): what the project's text outputs (JSON, HTML, messages) can carry.

#include <cstddef>
#include <string>
#include <string_view>

namespace countershade {

// The length of the well-formed sequence of two to four bytes at `at`, or 0: no overlong forms,
// no surrogates, nothing past U+10FFFF. (ASCII bytes are sequences of one, not counted here.)
size_t utf8_sequence(std::string_view text, size_t at);

// Whether every byte of `text` is ASCII or part of a well-formed sequence.
bool is_utf8(std::string_view text);

// The code points of `text`, U+FFFD for each byte that starts no well-formed sequence.
std::u32string decode_utf8(std::string_view text);

}  // namespace countershade
