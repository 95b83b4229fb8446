#pragma once
// Runs the adjustment app's real binary on a private X server, for the GUI tests.

#include <filesystem>
#include <string>
#include <vector>

#include "x_display.h"

namespace countershade::testing {

// `countershade adjust MANIFEST --subject SUBJECT --sessions SESSIONS`, then `extra`.
inline std::vector<std::string> adjust_args(const std::filesystem::path& manifest,
                                            const std::filesystem::path& sessions,
                                            const std::string& subject,
                                            std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {COUNTERSHADE_BINARY, "adjust", manifest.string(),
                                   "--subject",         subject,  "--sessions",
                                   sessions.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

// Runs the app to its end (a hang is cut off after 5 minutes) and returns its exit status.
inline int run_app(const XvfbServer& x, const std::vector<std::string>& args,
                   const std::filesystem::path& log) {
  Child app(args, x.display(), log.string());
  return app.wait(300);
}

}  // namespace countershade::testing
