#include "cli/display_flags.h"

namespace countershade::cli {

void add_output_path_flags(CLI::App* cmd, runtime::OutputPathChoice& path,
                           std::optional<uint32_t>& dither_seed) {
  cmd->add_option_function<std::string>(
         "--output-path",
         [&path](const std::string& text) { path = *runtime::parse_output_path(text); },
         "How a 16-bit set reaches the screen: ten-bit (a 10-bit framebuffer, checked by reading "
         "it back), dither "
         "(a seeded dither to 8 bits whose mean over 64 frames is the 16-bit value), pseudo-grey "
         "(bit stealing: 1786 "
         "grey levels on 8 bits, achromatic sets only), or auto (ten-bit where the check holds, "
         "else dither) [auto]")
      ->check(CLI::IsMember({"auto", "ten-bit", "dither", "pseudo-grey"}));
  cmd->add_option(
      "--dither-seed", dither_seed,
      "The dither's seed (default: the session's seed); recorded in the session's sidecar");
}

}  // namespace countershade::cli
