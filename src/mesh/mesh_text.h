#pragma once
// Small helpers for reading the text of mesh files (PLY headers, OFF lines).

#include <charconv>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace countershade {

// The whitespace-separated words of a line.
inline std::vector<std::string> split_words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

// What separates the words of an ASCII body (PLY, OFF): C's whitespace.
inline bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

// A whole non-negative decimal integer, or false.
inline bool parse_count(const std::string& text, unsigned long long& value) {
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && ptr == end;
}

// A word that is wholly a decimal number (strtod's syntax, so also "nan" and "inf"), or false.
inline bool parse_number(const std::string& word, double& value) {
  char* end = nullptr;
  value = std::strtod(word.c_str(), &end);
  return !word.empty() && end == word.c_str() + word.size();
}

}  // namespace countershade
