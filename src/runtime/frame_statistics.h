#pragma once
// The frame timing of a run, as the sidecar's `frames` records it (docs/adjustment-study.md, "What
// a session writes"): the intervals between swaps, the time to draw a frame, dropped frames
// (an interval over 1.2 refresh periods) and how long a key press takes to reach the screen.
// Times are seconds since the run's first frame.

#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace countershade::runtime {

class FrameStatistics {
 public:
  // A key pressed at `t`, to be shown by a frame still to come.
  void pressed(double t) { pending_.push_back({t, frame_}); }
  // The frame being swapped shows every press before it; `t` is when its drawing ended.
  void shown(double t);
  // A frame's swap came back at `t` after `draw_seconds` of drawing. `timed`: false for a frame
  // that wrote a screenshot (a test's or a demo's, never a participant's). `key_held`: an arrow
  // key was held (auto-repeat).
  void swapped(double t, double draw_seconds, bool timed, bool key_held, double refresh_hz);
  // Frames swapped so far.
  int frames() const { return frame_; }

  nlohmann::ordered_json to_json(const std::string& pacing, double refresh_hz) const;

 private:
  std::vector<float> all_, held_;    // intervals in seconds
  std::vector<float> draw_;          // time to build, render and swap a frame
  std::vector<double> dropped_at_;   // session time of the first dropped frames
  std::vector<float> key_to_frame_;  // from a key press to the swap of the frame that shows it
  int key_to_frame_frames_ = 0;      // the most frames any press took to appear: 1 is the next
  std::vector<std::pair<double, int>> pending_;  // presses not yet on screen: time, frames before
  double last_ = -1;
  int frame_ = 0;
};

}  // namespace countershade::runtime
