#include "runtime/key_script.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/file_bytes.h"

namespace countershade::runtime {

namespace {

constexpr double kMaxScriptDelayMs = 3.6e6;  // one hour
constexpr double kTapSeconds = 0.020;        // how long a scripted key press is held

struct KeyName {
  Key key;
  const char* name;
};
constexpr KeyName kKeyNames[] = {
    {Key::up, "up"},         {Key::down, "down"},   {Key::left, "left"},
    {Key::right, "right"},   {Key::enter, "enter"}, {Key::backspace, "backspace"},
    {Key::escape, "escape"}, {Key::quit, "q"},      {Key::one, "1"},
    {Key::two, "2"},         {Key::three, "3"},     {Key::four, "4"}};

}  // namespace

const char* key_name(Key key) {
  for (const auto& k : kKeyNames)
    if (k.key == key) return k.name;
  return "?";
}

std::optional<Key> key_from_name(const std::string& name) {
  for (const auto& k : kKeyNames)
    if (name == k.name) return k.key;
  return std::nullopt;
}

namespace {

// A line's delay in milliseconds, between 0 and an hour.
double parse_delay_ms(const std::string& text, const std::string& where) {
  double delay_ms = 0;
  try {
    size_t used = 0;
    delay_ms = std::stod(text, &used);
    if (used != text.size()) throw std::invalid_argument("");
  } catch (const std::exception&) {
    throw_input_error(where, "'" + text + "' is not a delay in milliseconds");
  }
  if (!(delay_ms >= 0) || !(delay_ms <= kMaxScriptDelayMs))
    throw_input_error(
        where,
        "the delay must be between 0 and 3600000 milliseconds (an hour; a longer pause is a typo)");
  return delay_ms;
}

// The events of one action at time_s: a screenshot or close, a held key, or a tapped key.
void add_action(const std::string& action, std::istringstream& words, double time_s,
                const std::string& where, std::vector<InputEvent>& events) {
  if (action == "screenshot" || action == "close") {
    events.push_back({time_s,
                      action == "close" ? InputEvent::Kind::close : InputEvent::Kind::screenshot,
                      Key::enter});
    return;
  }
  if (action == "hold") {
    std::string key_text;
    double hold_ms = -1;
    if (!(words >> key_text >> hold_ms) || !(hold_ms >= 0))
      throw_input_error(where, "expected 'hold KEY MILLISECONDS'");
    if (!(hold_ms <= kMaxScriptDelayMs))
      throw_input_error(where, "a key is held for at most 3600000 milliseconds (an hour)");
    const auto key = key_from_name(key_text);
    if (!key) throw_input_error(where, "unknown key '" + key_text + "'");
    events.push_back({time_s, InputEvent::Kind::press, *key});
    events.push_back({time_s + hold_ms / 1000, InputEvent::Kind::release, *key});
    return;
  }
  const auto key = key_from_name(action);
  if (!key)
    throw_input_error(where, "unknown action '" + action +
                                 "' (expected up, down, left, right, enter, backspace, escape, q, "
                                 "1 to 4, hold, screenshot or close)");
  events.push_back({time_s, InputEvent::Kind::press, *key});
  events.push_back({time_s + kTapSeconds, InputEvent::Kind::release, *key});
}

}  // namespace

std::vector<InputEvent> parse_key_script_text(const std::string& text, const std::string& file) {
  std::vector<InputEvent> events;
  std::istringstream lines(text);
  std::string line;
  double time_s = 0;
  for (int number = 1; std::getline(lines, line); ++number) {
    if (auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream words(line);
    std::string delay_text, action;
    if (!(words >> delay_text)) continue;
    const std::string where = file + ": line " + std::to_string(number);
    const double delay_ms = parse_delay_ms(delay_text, where);
    if (!(words >> action)) throw_input_error(where, "missing action after the delay");
    time_s += delay_ms / 1000;
    add_action(action, words, time_s, where, events);
    std::string extra;
    if (words >> extra)
      throw_input_error(where, "unexpected '" + extra + "' at the end of the line");
  }
  std::stable_sort(events.begin(), events.end(),
                   [](const auto& a, const auto& b) { return a.time_s < b.time_s; });
  return events;
}

std::filesystem::path screenshot_path(const std::filesystem::path& base, int n) {
  if (n == 0) return base;
  return base.parent_path() /
         (base.stem().string() + "-" + std::to_string(n + 1) + base.extension().string());
}

std::vector<InputEvent> parse_key_script(const std::filesystem::path& path) {
  return parse_key_script_text(read_file_bytes(path), path.string());
}

}  // namespace countershade::runtime
