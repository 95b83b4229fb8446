#pragma once
// A property bag of method parameters (in the manner of pbrt-v4's ParameterDictionary and
// Mitsuba 3's Properties). Experiment files and command-line flags both become one, so every
// method has exactly one parser, and a key that its parser never reads is reported by name.
//
// Keys are snake_case ("sigma_px"). On the command line they are written in kebab-case
// ("--sigma-px 4", "--sigma-px=4"); a bare flag is true and "--no-adapt" sets "adapt" to false.

#include <glm/vec3.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/json_reader.h"

namespace countershade {

// A documented parameter of a bag's owner (a method, a procedure), for `countershade methods`,
// `countershade procedures` and --help.
struct ParameterDoc {
  std::string key, default_value, help;
};

class ParameterBag {
 public:
  ParameterBag() = default;
  // The keys of a JSON object, except `skip` (keys that the caller reads itself). Messages name
  // "<file>: <path>.<key>".
  static ParameterBag from_json(const nlohmann::json& object, const std::string& file,
                                const std::string& path, const std::set<std::string>& skip = {});
  // Command-line words. Throws InputError for a word that is not a "--name".
  static ParameterBag from_arguments(const std::vector<std::string>& words);

  // Adds or replaces a value given by the program (e.g. one σ of an experiment's list).
  void set(const std::string& key, nlohmann::json value, const std::string& where);

  bool has(const std::string& key) const;
  // Given with a value other than JSON null (null means "not set", as in PsychoPy's arguments).
  bool given(const std::string& key) const;

  // Typed reads; each marks the key as a parameter of the reader. A value of the wrong type, or
  // NaN or infinity, is an InputError naming the key.
  double number(const std::string& key, double fallback) const;
  std::optional<double> optional_number(const std::string& key) const;
  // A number the owner cannot do without: its absence is an InputError naming the key.
  double required_number(const std::string& key) const;
  double number_in(const std::string& key, double fallback, double lo, double hi) const;
  long long integer_in(const std::string& key, long long fallback, long long lo,
                       long long hi) const;
  std::optional<long long> optional_integer(const std::string& key, long long lo,
                                            long long hi) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::string choice(const std::string& key, const std::string& fallback,
                     const std::vector<std::string>& choices) const;
  glm::dvec3 vec3(const std::string& key, const glm::dvec3& fallback) const;
  std::vector<double> numbers(const std::string& key, const std::vector<double>& fallback) const;
  // A list the owner cannot do without: its absence is an InputError naming the key.
  std::vector<double> required_numbers(const std::string& key) const;
  // The value as written (a JSON number, or the command line's text), for parameters with their
  // own syntax such as "5%".
  std::optional<std::string> text(const std::string& key) const;

  // A value with a structure of its own (an object, a list of objects), for its owner to read
  // strictly with JsonObject: the value, and the file and key path that name it in messages.
  // Marks the key as read; nullopt when absent. On the command line such a key is an InputError.
  struct Structured {
    const nlohmann::json& value;
    std::string file, path;
    // The value read as an object, its messages naming the file and key path.
    JsonObject object() const { return JsonObject(value, file, path); }
  };
  std::optional<Structured> structured(const std::string& key) const;

  // "experiment.json: methods[1]": the object itself (empty on the command line).
  const std::string& location() const { return location_; }
  // "--sigma-px" or "experiment.json: methods[1].sigma_px".
  std::string where(const std::string& key) const;
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  // Reports the first key that no read asked for: "<where>: <owner> has no parameter '<key>'
  // (its parameters: …)". Call after reading everything.
  void finish(const std::string& owner) const;

  // The values as given, for records.
  nlohmann::ordered_json to_json() const;
  // The fallback each typed read used so far, by key (the last read's, where a key is read twice),
  // so that a test can hold a method's documented defaults to what its parser does.
  const std::map<std::string, nlohmann::json>& fallbacks() const { return fallbacks_; }

 private:
  struct Entry {
    nlohmann::json value;
    std::string where;
    bool from_text = false;  // command-line text, converted on read
    size_t order = 0;        // as given, so that an error names the first unknown key typed
  };
  const Entry* find(const std::string& key) const;
  std::string known_list() const;

  std::map<std::string, Entry> entries_;
  bool command_line_ = false;
  std::string prefix_;       // "<file>: <path>." of a JSON object, to name keys it lacks
  std::string file_, path_;  // of a JSON object
  std::string location_;     // "<file>: <path>"
  mutable std::set<std::string> known_;
  mutable std::map<std::string, nlohmann::json> fallbacks_;
};

// "sigma_px" <-> "sigma-px".
std::string kebab_case(const std::string& key);

}  // namespace countershade
