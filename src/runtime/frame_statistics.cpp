#include "runtime/frame_statistics.h"

#include <algorithm>

namespace countershade::runtime {
namespace {

using OrderedJson = nlohmann::ordered_json;

// Count, mean and percentiles in ms; with period > 0 also the values over 1.2 periods (dropped).
OrderedJson summary(std::vector<float> v, double period) {
  OrderedJson j = {{"count", v.size()}};
  if (v.empty()) return j;
  std::sort(v.begin(), v.end());
  double sum = 0;
  for (float x : v) sum += x;
  auto pct = [&](double p) {
    return 1000.0 * v[std::min(v.size() - 1, size_t(p * double(v.size() - 1) + 0.5))];
  };
  j["mean_ms"] = 1000.0 * sum / double(v.size());
  j["median_ms"] = pct(0.5);
  j["p95_ms"] = pct(0.95);
  j["p99_ms"] = pct(0.99);
  j["max_ms"] = 1000.0 * v.back();
  if (period > 0)
    j["dropped"] = std::count_if(v.begin(), v.end(), [&](float x) { return x > 1.2 * period; });
  return j;
}

}  // namespace

void FrameStatistics::shown(double t) {
  // frame_ counts the frames before the one being swapped, which is the first to show these.
  for (const auto& [pressed, frames_before] : pending_) {
    key_to_frame_.push_back(float(t - pressed));
    key_to_frame_frames_ = std::max(key_to_frame_frames_, frame_ + 1 - frames_before);
  }
  pending_.clear();
}

void FrameStatistics::swapped(double t, double draw_seconds, bool timed, bool key_held,
                              double refresh_hz) {
  if (last_ >= 0 && frame_ > 20 && timed) {  // the first frames calibrate the pacing
    const double interval = t - last_;
    all_.push_back(float(interval));
    draw_.push_back(float(draw_seconds));
    if (key_held) held_.push_back(float(interval));
    if (interval > 1.2 / refresh_hz && dropped_at_.size() < 100) dropped_at_.push_back(t);
  }
  last_ = t;
  ++frame_;
}

OrderedJson FrameStatistics::to_json(const std::string& pacing, double refresh_hz) const {
  const double period = 1.0 / refresh_hz;
  return {{"pacing", pacing},
          {"period_ms", 1000 * period},
          {"dropped_threshold_ms", 1200 * period},
          {"all", summary(all_, period)},
          {"key_held", summary(held_, period)},
          {"draw", summary(draw_, period)},
          {"dropped_at_s", dropped_at_},
          {"key_to_frame", summary(key_to_frame_, 0)},
          {"key_to_frame_frames_max", key_to_frame_frames_}};
}

}  // namespace countershade::runtime
