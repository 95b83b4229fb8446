#include "core/time.h"

#include <chrono>
#include <cstdio>
#include <ctime>

namespace countershade {

std::string utc_timestamp(bool milliseconds) {
  auto now = std::chrono::system_clock::now();
  std::time_t t = std::chrono::system_clock::to_time_t(now);
  auto ms =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%04d-%02d-%02dT%02d:%02d:%02d", tm.tm_year + 1900,
                tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec);
  std::string out = buffer;
  if (milliseconds) {
    std::snprintf(buffer, sizeof buffer, ".%03d", int(ms));
    out += buffer;
  }
  return out + "Z";
}

}  // namespace countershade
