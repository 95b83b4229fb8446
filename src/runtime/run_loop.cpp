#include "runtime/run_loop.h"

#include "runtime/image_decode.h"
#include "runtime/signals.h"

namespace countershade::runtime {

RunLoop::RunLoop(Presenter& presenter, const Study& study, RunInputs inputs)
    : presenter_(presenter), study_(study), inputs_(std::move(inputs)) {}

RunEnd RunLoop::run() {
  preload();
  if (end_) return *end_;
  t0_ = presenter_.now();
  while (!end_) {
    const double now = presenter_.now() - t0_;
    take_input(now);
    if (end_) break;
    advance(now);
    draw_frame();
    if ((inputs_.scripted || inputs_.observed) && finished_unattended()) end_ = RunEnd::completed;
    if (inputs_.scripted && !inputs_.observed && inputs_.script.exhausted() && !end_)
      end_ = RunEnd::script_ended;
  }
  return *end_;
}

nlohmann::ordered_json RunLoop::frame_statistics() const {
  return frames_.to_json(presenter_.pacing(), presenter_.refresh_hz());
}

// Every stimulus as a texture, with a progress bar.
void RunLoop::preload() {
  auto loaded = preload_study(presenter_, study_);
  if (loaded.textures)
    textures_ = std::move(*loaded.textures);
  else
    end_ = RunEnd::closed;
  preloaded(loaded.record);
}

// Window events, the script's due events, the observer's, and signals.
void RunLoop::take_input(double now) {
  for (const auto& w : presenter_.poll_events()) {
    if (w.kind == WindowEvent::Kind::close)
      end_ = RunEnd::closed;
    else
      window_event(w, w.time_s - t0_);
  }
  while (!end_) {
    const auto e = inputs_.script.next_due(now);
    if (!e) break;
    if (e->kind == InputEvent::Kind::screenshot)
      screenshot_due_ = true;
    else if (e->kind == InputEvent::Kind::close)
      end_ = RunEnd::closed;
    else
      input(*e);
  }
  if (inputs_.observed) observe(now);
  if (const auto signal = SignalGuard::pending()) end_ = signal;
}

void RunLoop::draw_frame() {
  std::filesystem::path shot;
  if (screenshot_due_ && inputs_.screenshot)
    shot = screenshot_path(*inputs_.screenshot, screenshots_);
  const double draw_start = presenter_.now();
  const FrameContent shown = content(draw_start - t0_);
  const StimulusLayout layout = presenter_.draw(shown, shot);
  const double draw_seconds = presenter_.now() - draw_start;
  frames_.shown(presenter_.now() - t0_);
  if (!shot.empty()) {
    describe(shot, shown, layout, draw_start - t0_);
    ++screenshots_;
    screenshot_due_ = false;
  }
  presenter_.pace();
  frames_.swapped(presenter_.now() - t0_, draw_seconds, shot.empty(), key_held(),
                  presenter_.refresh_hz());
}

}  // namespace countershade::runtime
