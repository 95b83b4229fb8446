#pragma once
// A token bucket per key (a participant's token, or an address for claims): `rate` requests a
// second on average, bursts of up to `burst`. A page sends one row at a time, a few seconds apart,
// so the limit only ever stops a script.

#include <chrono>
#include <mutex>
#include <string>
#include <unordered_map>

namespace countershade::serve {

class RateLimit {
 public:
  RateLimit(double rate, double burst) : rate_(rate), burst_(burst) {}

  // Whether one more request of `key` may go through now (and counts it if so).
  bool allow(const std::string& key) {
    const auto now = std::chrono::steady_clock::now();
    std::lock_guard lock(mutex_);
    auto [bucket, fresh] = buckets_.try_emplace(key, Bucket{burst_, now});
    Bucket& b = bucket->second;
    const double seconds = std::chrono::duration<double>(now - b.last).count();
    b.tokens = std::min(burst_, b.tokens + seconds * rate_);
    b.last = now;
    if (b.tokens < 1) return false;
    b.tokens -= 1;
    return true;
  }

 private:
  struct Bucket {
    double tokens;
    std::chrono::steady_clock::time_point last;
  };
  double rate_, burst_;
  std::mutex mutex_;
  std::unordered_map<std::string, Bucket> buckets_;
};

}  // namespace countershade::serve
