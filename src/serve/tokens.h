#pragma once
// Participant and admin tokens: 128 random bits as 32 lowercase hex digits. The database keeps
// only their SHA-256, so a copy of it lets no one write as a participant.

#include <string>

namespace countershade::serve {

// A fresh token from the kernel's random source (getrandom).
std::string random_token();

// Whether `text` has a token's form (32 lowercase hex digits).
bool is_token(const std::string& text);

// What the database keeps of a token.
std::string token_hash(const std::string& token);

}  // namespace countershade::serve
