#pragma once
// The run loop both apps share: preload every stimulus, then frame after frame take the input
// (window, key script, simulated observer, signals), let the study move on, draw and pace, until
// the study, the participant, the window, a signal or the script ends the run. A study (the
// adjustment procedure, the forced-choice trials) fills in the hooks and never sees the window.

#include <filesystem>
#include <optional>
#include <vector>

#include "runtime/frame_statistics.h"
#include "runtime/key_script.h"
#include "runtime/presenter.h"
#include "runtime/session_run.h"
#include "runtime/study.h"

namespace countershade::runtime {

struct RunInputs {
  ScriptedInput script;
  bool scripted = false;  // a --script was given (its end ends the run, unless an observer plays)
  bool observed = false;  // a simulated observer plays
  std::optional<std::filesystem::path> screenshot;  // where a script's screenshots go
};

class RunLoop {
 public:
  RunLoop(Presenter& presenter, const Study& study, RunInputs inputs);
  virtual ~RunLoop() = default;
  RunLoop(const RunLoop&) = delete;
  RunLoop& operator=(const RunLoop&) = delete;

  // Runs until the run ends; returns how. Signals must be routed (SignalGuard) by the caller.
  RunEnd run();
  nlohmann::ordered_json frame_statistics() const;

 protected:
  // The preload is done; `textures` are empty when the window was closed meanwhile.
  virtual void preloaded(const Preload& record) = 0;
  // A window event other than close; `t` is seconds since the first frame.
  virtual void window_event(const WindowEvent& event, double t) = 0;
  // A key press or release from the script or the observer.
  virtual void input(const InputEvent& event) = 0;
  // The simulated observer's turn.
  virtual void observe(double now) { (void)now; }
  // Changes that come with time (a held key's repeats, the end of feedback).
  virtual void advance(double now) { (void)now; }
  virtual FrameContent content(double t) const = 0;
  // Writes the screenshot's record of what was shown where.
  virtual void describe(const std::filesystem::path& shot, const FrameContent& content,
                        const StimulusLayout& layout, double t) const = 0;
  // Whether an arrow key is held (for the frame statistics).
  virtual bool key_held() const { return false; }
  // Whether a scripted or observed run is over by itself (no Enter needed on the last screen).
  virtual bool finished_unattended() const { return false; }

  void end(RunEnd how) { end_ = how; }
  bool ended() const { return end_.has_value(); }
  // A key press, for the key-to-frame latency.
  void note_press(double t) { frames_.pressed(t); }
  const std::vector<unsigned>& textures() const { return textures_; }
  // Frames swapped so far.
  int frames_drawn() const { return frames_.frames(); }
  Presenter& presenter() const { return presenter_; }

 private:
  void preload();
  void take_input(double now);
  void draw_frame();

  Presenter& presenter_;
  const Study& study_;
  RunInputs inputs_;
  std::vector<unsigned> textures_;
  std::optional<RunEnd> end_;
  double t0_ = 0;
  bool screenshot_due_ = false;
  int screenshots_ = 0;
  FrameStatistics frames_;
};

}  // namespace countershade::runtime
