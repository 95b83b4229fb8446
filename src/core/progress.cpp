#include "core/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace countershade {

std::string format_seconds(double seconds) {
  char buffer[32];
  if (seconds < 60)
    std::snprintf(buffer, sizeof buffer, "%.1f s", seconds);
  else
    std::snprintf(buffer, sizeof buffer, "%d min %02d s", int(seconds) / 60, int(seconds) % 60);
  return buffer;
}

Progress::Progress(std::string label)
    : label_(std::move(label)),
      terminal_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

void Progress::update(double fraction) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto now = std::chrono::steady_clock::now();
  double elapsed = std::chrono::duration<double>(now - start_).count();
  if (terminal_) {
    if (fraction < 1.0 && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    constexpr int kWidth = 30;
    int filled = int(std::lround(fraction * kWidth));
    std::string bar(size_t(filled), '#');
    bar.resize(kWidth, ' ');
    std::string eta = fraction > 0.02 ? format_seconds(elapsed * (1.0 - fraction) / fraction) : "?";
    std::fprintf(stderr, "\r%s [%s] %3d%%  ETA %s   ", label_.c_str(), bar.c_str(),
                 int(fraction * 100), eta.c_str());
    std::fflush(stderr);
  } else {
    // Plain logs (CI, pipes): one line per 10%, and nothing at all for runs under two seconds.
    int decile = int(fraction * 10);
    if (decile <= last_logged_decile_ || decile >= 10 || elapsed < 2.0) return;
    last_logged_decile_ = decile;
    std::fprintf(stderr, "%s: %d%% (%s)\n", label_.c_str(), decile * 10,
                 format_seconds(elapsed).c_str());
  }
}

void Progress::finish(const std::string& summary) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (terminal_) std::fprintf(stderr, "\r\033[K");
  std::fprintf(stderr, "%s: %s\n", label_.c_str(), summary.c_str());
}

}  // namespace countershade
