#pragma once
// The keys a study answers with, and key input that does not come from a person: a timed key
// script (--script) produces the same events the window's key callback produces, so tests
// exercise the real session loop.

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace countershade::runtime {

// one … four: the number keys (top row or keypad), for forced-choice answers.
enum class Key { up, down, left, right, enter, backspace, escape, quit, one, two, three, four };

struct InputEvent {
  enum class Kind { press, release, screenshot, close };
  double time_s = 0;  // since the first frame after preloading
  Kind kind = Kind::press;
  Key key = Key::enter;
};

// Reads a key script. Each line is "<delay_ms> <action>", the delay counted from the previous
// line; '#' starts a comment. Actions: up, down, left, right, enter, backspace, escape, q (a press
// and a release 20 ms later); "hold KEY MS" (a key held for MS ms, which auto-repeats);
// "screenshot"; "close" (the window's close button). Throws InputError naming the line.
std::vector<InputEvent> parse_key_script(const std::filesystem::path& path);
std::vector<InputEvent> parse_key_script_text(const std::string& text, const std::string& file);

// A key script being played: the events due by a time, in order, each once.
class ScriptedInput {
 public:
  ScriptedInput() = default;
  explicit ScriptedInput(std::vector<InputEvent> events) : events_(std::move(events)) {}
  // The next event if it is due at `now` (seconds since the first frame).
  std::optional<InputEvent> next_due(double now) {
    if (next_ >= events_.size() || events_[next_].time_s > now) return std::nullopt;
    return events_[next_++];
  }
  bool exhausted() const { return next_ == events_.size(); }

 private:
  std::vector<InputEvent> events_;
  size_t next_ = 0;
};

// The file of the n-th screenshot (0-based) of a run asked for `base`: base itself, then
// "stem-2.png", "stem-3.png", …
std::filesystem::path screenshot_path(const std::filesystem::path& base, int n);

// Key names for scripts and the trajectory log.
const char* key_name(Key key);
std::optional<Key> key_from_name(const std::string& name);

}  // namespace countershade::runtime
