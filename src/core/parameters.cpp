#include "core/parameters.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "core/error.h"
#include "core/json_reader.h"

namespace countershade {
namespace {

std::string snake_case(std::string name) {
  for (char& c : name)
    if (c == '-') c = '_';
  return name;
}

// Full-string parse of a finite number; nullopt otherwise.
std::optional<double> parse_number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  errno = 0;
  double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) parts.push_back(part);
  return parts;
}

std::string format_bound(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

std::string kebab_case(const std::string& key) {
  std::string out = key;
  for (char& c : out)
    if (c == '_') c = '-';
  return out;
}

ParameterBag ParameterBag::from_json(const nlohmann::json& object, const std::string& file,
                                     const std::string& path, const std::set<std::string>& skip) {
  ParameterBag bag;
  bag.prefix_ = file + ": " + (path.empty() ? "" : path + ".");
  bag.location_ = file + (path.empty() ? "" : ": " + path);
  bag.file_ = file;
  bag.path_ = path;
  if (!object.is_object())
    throw_input_error(file + (path.empty() ? "" : ": " + path),
                      "expected an object, got " + json_type_name(object));
  for (auto it = object.begin(); it != object.end(); ++it) {
    if (skip.count(it.key())) continue;
    const size_t order = bag.entries_.size();
    bag.entries_[it.key()] = {it.value(), file + ": " + (path.empty() ? "" : path + ".") + it.key(),
                              false, order};
  }
  return bag;
}

ParameterBag ParameterBag::from_arguments(const std::vector<std::string>& words) {
  ParameterBag bag;
  bag.command_line_ = true;
  for (size_t i = 0; i < words.size(); ++i) {
    const std::string& word = words[i];
    if (word.size() < 3 || word.compare(0, 2, "--") != 0)
      throw InputError("unexpected argument '" + word + "' (parameters are written --name value)");
    std::string name = word.substr(2), value;
    bool has_value = false;
    if (auto eq = name.find('='); eq != std::string::npos) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
      has_value = true;
    } else if (i + 1 < words.size() && words[i + 1].compare(0, 2, "--") != 0) {
      value = words[++i];
      has_value = true;
    }
    std::string key = snake_case(name);
    if (!has_value && key.compare(0, 3, "no_") == 0) {
      key = key.substr(3);
      value = "false";
    } else if (!has_value) {
      value = "true";
    }
    if (bag.entries_.count(key)) throw InputError("--" + kebab_case(key) + ": given twice");
    const size_t order = bag.entries_.size();
    bag.entries_[key] = {value, "--" + kebab_case(key), true, order};
  }
  return bag;
}

void ParameterBag::set(const std::string& key, nlohmann::json value, const std::string& where) {
  const size_t order = entries_.count(key) ? entries_[key].order : entries_.size();
  entries_[key] = {std::move(value), where, false, order};
}

const ParameterBag::Entry* ParameterBag::find(const std::string& key) const {
  known_.insert(key);
  auto it = entries_.find(key);
  return it == entries_.end() ? nullptr : &it->second;
}

bool ParameterBag::has(const std::string& key) const { return find(key) != nullptr; }

bool ParameterBag::given(const std::string& key) const {
  const Entry* e = find(key);
  return e && !e->value.is_null();
}

std::string ParameterBag::where(const std::string& key) const {
  auto it = entries_.find(key);
  if (it != entries_.end()) return it->second.where;
  return command_line_ ? "--" + kebab_case(key) : prefix_ + key;
}

void ParameterBag::fail(const std::string& key, const std::string& what) const {
  throw_input_error(where(key), what);
}

std::optional<double> ParameterBag::optional_number(const std::string& key) const {
  const Entry* e = find(key);
  if (!e) return std::nullopt;
  if (e->from_text) {
    auto v = parse_number(e->value.get<std::string>());
    if (!v) fail(key, "expected a finite number, got '" + e->value.get<std::string>() + "'");
    return v;
  }
  if (!e->value.is_number()) fail(key, "expected a number, got " + json_type_name(e->value));
  double v = e->value.get<double>();
  if (!std::isfinite(v)) fail(key, "must be finite");
  return v;
}

double ParameterBag::required_number(const std::string& key) const {
  const auto v = optional_number(key);
  if (!v) fail(key, "missing required key");
  return *v;
}

double ParameterBag::number(const std::string& key, double fallback) const {
  fallbacks_[key] = fallback;
  return optional_number(key).value_or(fallback);
}

double ParameterBag::number_in(const std::string& key, double fallback, double lo,
                               double hi) const {
  double v = number(key, fallback);
  if (v < lo || v > hi)
    fail(key,
         "must be in [" + format_bound(lo) + ", " + format_bound(hi) + "], got " + format_bound(v));
  return v;
}

std::optional<long long> ParameterBag::optional_integer(const std::string& key, long long lo,
                                                        long long hi) const {
  auto v = optional_number(key);
  if (!v) return std::nullopt;
  if (*v != std::floor(*v) || *v < double(lo) || *v > double(hi))
    fail(key, "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                  "], got " + format_bound(*v));
  return (long long)*v;
}

long long ParameterBag::integer_in(const std::string& key, long long fallback, long long lo,
                                   long long hi) const {
  fallbacks_[key] = fallback;
  return optional_integer(key, lo, hi).value_or(fallback);
}

bool ParameterBag::boolean(const std::string& key, bool fallback) const {
  fallbacks_[key] = fallback;
  const Entry* e = find(key);
  if (!e) return fallback;
  if (!e->from_text) {
    if (!e->value.is_boolean())
      fail(key, "expected true or false, got " + json_type_name(e->value));
    return e->value.get<bool>();
  }
  const std::string t = e->value.get<std::string>();
  if (t == "true" || t == "1" || t == "yes" || t == "on") return true;
  if (t == "false" || t == "0" || t == "no" || t == "off") return false;
  fail(key, "expected true or false, got '" + t + "'");
}

std::optional<ParameterBag::Structured> ParameterBag::structured(const std::string& key) const {
  const Entry* e = find(key);
  if (!e) return std::nullopt;
  if (command_line_) fail(key, "has a structure of its own; give it in a JSON file");
  return Structured{e->value, file_, path_.empty() ? key : path_ + "." + key};
}

std::optional<std::string> ParameterBag::text(const std::string& key) const {
  const Entry* e = find(key);
  if (!e) return std::nullopt;
  if (e->value.is_string()) return e->value.get<std::string>();
  if (e->value.is_number()) return e->value.dump();
  fail(key, "expected a number or a string, got " + json_type_name(e->value));
}

std::string ParameterBag::choice(const std::string& key, const std::string& fallback,
                                 const std::vector<std::string>& choices) const {
  fallbacks_[key] = fallback;
  const Entry* e = find(key);
  std::string v = fallback;
  if (e) {
    if (!e->value.is_string()) fail(key, "expected a string, got " + json_type_name(e->value));
    v = e->value.get<std::string>();
  }
  std::string list;
  for (const auto& c : choices) {
    if (v == c) return v;
    list += (list.empty() ? "" : ", ") + c;
  }
  fail(key, "unknown value '" + v + "' (expected one of: " + list + ")");
}

std::vector<double> ParameterBag::numbers(const std::string& key,
                                          const std::vector<double>& fallback) const {
  fallbacks_[key] = fallback;
  const Entry* e = find(key);
  if (!e) return fallback;
  std::vector<double> out;
  if (e->from_text) {
    for (const auto& part : split_commas(e->value.get<std::string>())) {
      auto v = parse_number(part);
      if (!v)
        fail(key,
             "expected comma-separated finite numbers, got '" + e->value.get<std::string>() + "'");
      out.push_back(*v);
    }
    return out;
  }
  if (e->value.is_number()) return {number(key, 0)};
  if (!e->value.is_array())
    fail(key, "expected an array of numbers, got " + json_type_name(e->value));
  for (const auto& v : e->value) {
    if (!v.is_number() || !std::isfinite(v.get<double>()))
      fail(key, "expected an array of finite numbers");
    out.push_back(v.get<double>());
  }
  return out;
}

std::vector<double> ParameterBag::required_numbers(const std::string& key) const {
  if (!has(key)) fail(key, "missing required key");
  std::vector<double> values = numbers(key, {});
  fallbacks_.erase(key);  // there is none
  return values;
}

glm::dvec3 ParameterBag::vec3(const std::string& key, const glm::dvec3& fallback) const {
  const bool given = has(key);
  std::vector<double> v = given ? numbers(key, {}) : std::vector<double>{};
  fallbacks_[key] =
      std::vector<double>{fallback.x, fallback.y, fallback.z};  // after numbers(), which records {}
  if (!given) return fallback;
  if (v.size() == 1) return glm::dvec3(v[0]);
  if (v.size() != 3)
    fail(key, command_line_ ? "expected three numbers R,G,B" : "expected an array of 3 numbers");
  return {v[0], v[1], v[2]};
}

std::string ParameterBag::known_list() const {
  std::string list;
  for (const auto& k : known_)
    list += (list.empty() ? "" : ", ") + (command_line_ ? "--" + kebab_case(k) : k);
  return list.empty() ? "it takes no parameters" : list;
}

void ParameterBag::finish(const std::string& owner) const {
  const std::pair<const std::string, Entry>* first = nullptr;
  for (const auto& item : entries_)
    if (!known_.count(item.first) && (!first || item.second.order < first->second.order))
      first = &item;
  if (!first) return;
  const auto& [key, entry] = *first;
  throw_input_error(
      entry.where, owner + " has no parameter '" + (command_line_ ? kebab_case(key) : key) + "' (" +
                       (known_.empty() ? known_list() : "its parameters: " + known_list()) + ")");
}

nlohmann::ordered_json ParameterBag::to_json() const {
  nlohmann::ordered_json out = nlohmann::ordered_json::object();
  for (const auto& [key, entry] : entries_) out[key] = entry.value;
  return out;
}

}  // namespace countershade
