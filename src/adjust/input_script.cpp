#include "adjust/input_script.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/file_bytes.h"
#include "core/random.h"

namespace countershade::adjust {

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

// A normal deviate from two counter-based uniforms (Box–Muller).
double normal(SampleStream& s) {
  double u1 = std::max(s.next(), 1e-300), u2 = s.next();
  return std::sqrt(-2 * std::log(u1)) * std::cos(2 * M_PI * u2);
}

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

std::vector<InputEvent> parse_key_script(const std::filesystem::path& path) {
  return parse_key_script_text(read_file_bytes(path), path.string());
}

uint64_t parse_observer_spec(const std::string& spec) {
  const std::string prefix = "simulated:";
  if (spec.rfind(prefix, 0) == 0) {
    std::string digits = spec.substr(prefix.size());
    if (!digits.empty() && digits.size() <= 15 &&
        std::all_of(digits.begin(), digits.end(), ::isdigit))
      return std::stoull(digits);
  }
  throw_input_error(
      "--observer",
      "'" + spec + "' is not an observer (expected simulated:SEED, e.g. simulated:1)");
}

// ---------------------------------------------------------------------------------------------

SimulatedObserver::SimulatedObserver(uint64_t seed, const Study& study, double step_interval_s)
    : seed_(seed), study_(study), interval_s_(step_interval_s) {}

double SimulatedObserver::latent_lambda(int condition, int repetition, Question question) const {
  const Condition& c = study_.conditions[size_t(condition)];
  const double top = study_.lambda(c.grid_size - 1);
  // The observer's thresholds for this condition (fixed over repetitions), plus answer noise.
  SampleStream person(seed_, hash_string(c.scene + "/" + c.method), uint64_t(c.sigma * 1e9), 0);
  const double low = 0.2 * top * std::exp(0.2 * normal(person));
  const double ratio[kQuestionCount] = {1.0, 3.0 * std::exp(0.1 * normal(person)),
                                        1.6 * std::exp(0.1 * normal(person))};
  SampleStream noise(seed_, hash_string(c.scene + "/" + c.method), uint64_t(c.sigma * 1e9),
                     uint64_t(repetition) * 8 + int(question) + 1);
  return low * ratio[int(question)] * std::exp(0.05 * normal(noise));
}

int SimulatedObserver::answer_index(int condition, int repetition, Question question) const {
  const Condition& c = study_.conditions[size_t(condition)];
  const double latent = latent_lambda(condition, repetition, question);
  for (int i = 0; i < c.grid_size; ++i)
    if (study_.lambda(i) >= latent - 1e-12) return i;
  return c.grid_size - 1;
}

std::vector<InputEvent> SimulatedObserver::act(const Procedure& p, double time_s) {
  if (time_s < next_action_s_ || p.done()) return {};
  next_action_s_ = time_s + interval_s_;
  Key key = Key::enter;
  if (p.phase() == Procedure::Phase::question) {
    const int target = answer_index(p.trial().condition, p.trial().repetition, p.question());
    if (p.lambda_index() < target)
      key = Key::right;
    else if (p.lambda_index() > target)
      key = Key::left;
  } else if (p.phase() == Procedure::Phase::paused) {
    key = Key::escape;
  }
  return {{time_s, InputEvent::Kind::press, key}, {time_s, InputEvent::Kind::release, key}};
}

}  // namespace countershade::adjust
