#pragma once
// The answers a procedure is replayed on (`countershade simulate --procedure P --responses R`):
// how a lab checks what a staircase or QUEST will do before running it.

#include <filesystem>
#include <vector>

namespace countershade::procedures {

// The `response` column (1 or Correct, 0 or Incorrect; one row per trial) of a CSV; anything else
// is an InputError naming the file, line and column.
std::vector<bool> read_binary_responses(const std::filesystem::path& path);

}  // namespace countershade::procedures
