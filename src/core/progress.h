#pragma once
// Progress reporting for long runs: a redrawn bar with ETA on a terminal, plain log lines
// otherwise.

#include <chrono>
#include <mutex>
#include <string>

namespace countershade {

class Progress {
 public:
  // Writes to stderr. `label` prefixes every line.
  explicit Progress(std::string label);
  // Thread-safe; `fraction` in [0,1]. Redraws at most ~10 times a second (terminal) or logs every
  // 10% (otherwise).
  void update(double fraction);
  // Ends the bar with a final line.
  void finish(const std::string& summary);

 private:
  std::string label_;
  bool terminal_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  int last_logged_decile_ = -1;
  std::mutex mutex_;
};

std::string format_seconds(double seconds);

}  // namespace countershade
