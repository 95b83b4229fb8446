#pragma once
// The keys a study answers with, and key input that does not come from a person: a timed key
// script (--script) produces the same events the window's key callback produces, so tests
// exercise the real session loop.

#include <filesystem>
#include <optional>
#include <string>
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

// Key names for scripts and the trajectory log.
const char* key_name(Key key);
std::optional<Key> key_from_name(const std::string& name);

}  // namespace countershade::runtime
