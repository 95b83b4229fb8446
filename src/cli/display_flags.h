#pragma once
// Flags both apps share: how 16-bit stimuli reach the screen.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>

#include "runtime/fine_levels.h"

namespace countershade::cli {

// --output-path auto|ten-bit|dither and --dither-seed N.
void add_output_path_flags(CLI::App* cmd, runtime::OutputPathChoice& path,
                           std::optional<uint32_t>& dither_seed);

}  // namespace countershade::cli
