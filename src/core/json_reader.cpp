#include "core/json_reader.h"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/file_bytes.h"

namespace countershade {

using nlohmann::json;

namespace {

// Parses JSON text. JSON allows repeated keys and nlohmann keeps the last one silently; in a
// configuration file a repeated key is almost always a mistake, so it is an error. Numbers too
// large for a double (1e400) are errors that name the file, not a library exception.
template <class Json>
Json parse_strict(const std::string& text, const std::string& file) {
  if (text.empty()) throw_input_error(file, "file is empty");
  std::vector<std::set<std::string>> keys;
  std::string duplicate;
  auto check = [&](int, typename Json::parse_event_t event, Json& parsed) {
    using Event = typename Json::parse_event_t;
    if (event == Event::object_start)
      keys.emplace_back();
    else if (event == Event::object_end && !keys.empty())
      keys.pop_back();
    else if (event == Event::key && !keys.empty() &&
             !keys.back().insert(parsed.template get<std::string>()).second && duplicate.empty())
      duplicate = parsed.template get<std::string>();
    return true;
  };
  try {
    Json value = Json::parse(text, check);
    if (!duplicate.empty())
      throw_input_error(file, "the key '" + duplicate + "' appears twice in one object");
    return value;
  } catch (const nlohmann::json::exception& e) {
    // nlohmann's message starts with "[json.exception.parse_error.101] "; keep the readable part.
    std::string message = e.what();
    auto pos = message.find("] ");
    if (pos != std::string::npos) message = message.substr(pos + 2);
    if (dynamic_cast<const nlohmann::json::out_of_range*>(&e))
      throw_input_error(file, "a number is too large for a double (" + message + ")");
    throw_input_error(file, "malformed JSON: " + message);
  }
}

}  // namespace

nlohmann::json parse_json_text(const std::string& text, const std::string& file) {
  return parse_strict<nlohmann::json>(text, file);
}

nlohmann::json parse_json_file(const std::filesystem::path& path) {
  return parse_strict<nlohmann::json>(read_file_bytes(path), path.string());
}

nlohmann::ordered_json parse_ordered_json_file(const std::filesystem::path& path) {
  return parse_strict<nlohmann::ordered_json>(read_file_bytes(path), path.string());
}

nlohmann::ordered_json parse_ordered_json_text(const std::string& text, const std::string& file) {
  return parse_strict<nlohmann::ordered_json>(text, file);
}

std::string json_type_name(const json& value) {
  switch (value.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return "a boolean";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return "a number";
    case json::value_t::string:
      return "a string";
    case json::value_t::array:
      return "an array";
    case json::value_t::object:
      return "an object";
    default:
      return "an unsupported value";
  }
}

JsonObject::JsonObject(const json& value, std::string file, std::string path)
    : value_(&value), file_(std::move(file)), path_(std::move(path)) {
  if (!value.is_object())
    throw_input_error(file_ + (path_.empty() ? "" : ": " + path_),
                      "expected an object, got " + json_type_name(value));
}

bool JsonObject::has(const std::string& key) const { return value_->contains(key); }

std::string JsonObject::key_path(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

void JsonObject::fail(const std::string& key, const std::string& what) const {
  throw_input_error(file_ + ": " + (key.empty() ? path_ : key_path(key)), what);
}

const json& JsonObject::at(const std::string& key) const {
  auto it = value_->find(key);
  if (it == value_->end()) fail(key, "missing required key");
  used_.insert(key);
  return *it;
}

const json& JsonObject::raw(const std::string& key) const { return at(key); }

double JsonObject::number(const std::string& key) const {
  const json& v = at(key);
  if (!v.is_number()) fail(key, "expected a number, got " + json_type_name(v));
  double d = v.get<double>();
  if (!std::isfinite(d)) fail(key, "must be finite");
  return d;
}

long long JsonObject::integer(const std::string& key) const {
  const json& v = at(key);
  if (v.is_number_unsigned() &&
      v.get<unsigned long long>() > 9007199254740992ull)  // 2^53: beyond every limit
    fail(key, "got " + std::to_string(v.get<unsigned long long>()) + ", which is too large");
  if (v.is_number_integer() || v.is_number_unsigned()) return v.get<long long>();
  if (v.is_number_float()) {
    double d = v.get<double>();
    if (std::isfinite(d) && d == std::floor(d) && std::abs(d) < 9e15) return (long long)d;
  }
  fail(key, "expected an integer, got " + json_type_name(v));
}

bool JsonObject::boolean(const std::string& key) const {
  const json& v = at(key);
  if (!v.is_boolean()) fail(key, "expected true or false, got " + json_type_name(v));
  return v.get<bool>();
}

std::string JsonObject::string(const std::string& key) const {
  const json& v = at(key);
  if (!v.is_string()) fail(key, "expected a string, got " + json_type_name(v));
  return v.get<std::string>();
}

glm::dvec3 JsonObject::vec3(const std::string& key) const {
  const json& v = at(key);
  if (v.is_number()) {  // a single number means a grey / uniform triple
    double d = v.get<double>();
    if (!std::isfinite(d)) fail(key, "must be finite");
    return glm::dvec3(d);
  }
  if (!v.is_array() || v.size() != 3) fail(key, "expected an array of 3 numbers");
  glm::dvec3 out;
  for (int i = 0; i < 3; ++i) {
    if (!v[i].is_number()) fail(key, "expected an array of 3 numbers");
    out[i] = v[i].get<double>();
    if (!std::isfinite(out[i])) fail(key, "must be finite");
  }
  return out;
}

JsonObject JsonObject::object(const std::string& key) const {
  return JsonObject(at(key), file_, key_path(key));
}

std::vector<JsonObject> JsonObject::objects(const std::string& key) const {
  const json& v = at(key);
  if (!v.is_array()) fail(key, "expected an array, got " + json_type_name(v));
  std::vector<JsonObject> out;
  for (size_t i = 0; i < v.size(); ++i)
    out.emplace_back(v[i], file_, key_path(key) + "[" + std::to_string(i) + "]");
  return out;
}

std::vector<double> JsonObject::numbers(const std::string& key) const {
  const json& v = at(key);
  if (!v.is_array()) fail(key, "expected an array of numbers, got " + json_type_name(v));
  std::vector<double> out;
  for (const json& e : v) {
    if (!e.is_number() || !std::isfinite(e.get<double>()))
      fail(key, "expected an array of finite numbers");
    out.push_back(e.get<double>());
  }
  return out;
}

double JsonObject::number_or(const std::string& key, double fallback) const {
  return has(key) ? number(key) : fallback;
}
long long JsonObject::integer_or(const std::string& key, long long fallback) const {
  return has(key) ? integer(key) : fallback;
}
bool JsonObject::boolean_or(const std::string& key, bool fallback) const {
  return has(key) ? boolean(key) : fallback;
}
std::string JsonObject::string_or(const std::string& key, const std::string& fallback) const {
  return has(key) ? string(key) : fallback;
}
glm::dvec3 JsonObject::vec3_or(const std::string& key, const glm::dvec3& fallback) const {
  return has(key) ? vec3(key) : fallback;
}

double JsonObject::number_in(const std::string& key, double fallback, double lo, double hi) const {
  double v = number_or(key, fallback);
  if (v < lo || v > hi) {
    std::ostringstream s;
    s << "must be in [" << lo << ", " << hi << "], got " << v;
    fail(key, s.str());
  }
  return v;
}

long long JsonObject::integer_in(const std::string& key, long long fallback, long long lo,
                                 long long hi) const {
  long long v = integer_or(key, fallback);
  if (v < lo || v > hi)
    fail(key, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
                  std::to_string(v));
  return v;
}

std::string JsonObject::choice(const std::string& key, const std::string& fallback,
                               const std::vector<std::string>& choices) const {
  std::string v = string_or(key, fallback);
  for (const auto& c : choices)
    if (v == c) return v;
  std::string list;
  for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c;
  fail(key, "unknown value '" + v + "' (expected one of: " + list + ")");
}

void JsonObject::finish() const {
  for (auto it = value_->begin(); it != value_->end(); ++it) {
    if (used_.count(it.key())) continue;
    fail(it.key(), "unknown key");
  }
}

}  // namespace countershade
