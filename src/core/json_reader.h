#pragma once
// Strict reading of JSON configuration files: every error names the file and the key path
// (e.g. "scene.json: objects[2].material.albedo: expected 3 numbers"), and keys that were never
// read are reported as unknown, which catches typos.

#include <filesystem>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace countershade {

// Parses a JSON file; a missing file or malformed JSON is an InputError naming the file.
nlohmann::json parse_json_file(const std::filesystem::path& path);
// The same, keeping the keys in the order they were written.
nlohmann::ordered_json parse_ordered_json_file(const std::filesystem::path& path);
// Parses JSON text with the same rules; `file` names it in messages.
nlohmann::json parse_json_text(const std::string& text, const std::string& file);
nlohmann::ordered_json parse_ordered_json_text(const std::string& text, const std::string& file);

class JsonObject {
 public:
  // `path` is the key path of this object inside `file` ("" for the root).
  JsonObject(const nlohmann::json& value, std::string file, std::string path);

  bool has(const std::string& key) const;
  std::string key_path(const std::string& key) const;
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  const nlohmann::json& value() const { return *value_; }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;

  // Required values (an absent key is an error).
  double number(const std::string& key) const;
  long long integer(const std::string& key) const;
  bool boolean(const std::string& key) const;
  std::string string(const std::string& key) const;
  glm::dvec3 vec3(const std::string& key) const;
  JsonObject object(const std::string& key) const;
  std::vector<JsonObject> objects(const std::string& key) const;  // array of objects
  std::vector<double> numbers(const std::string& key) const;      // array of numbers
  const nlohmann::json& raw(const std::string& key) const;        // marks the key as read

  // Optional values: the fallback when the key is absent.
  double number_or(const std::string& key, double fallback) const;
  long long integer_or(const std::string& key, long long fallback) const;
  bool boolean_or(const std::string& key, bool fallback) const;
  std::string string_or(const std::string& key, const std::string& fallback) const;
  glm::dvec3 vec3_or(const std::string& key, const glm::dvec3& fallback) const;

  // Range checks that report with the key path.
  double number_in(const std::string& key, double fallback, double lo, double hi) const;
  long long integer_in(const std::string& key, long long fallback, long long lo,
                       long long hi) const;
  // A string that must be one of `choices`.
  std::string choice(const std::string& key, const std::string& fallback,
                     const std::vector<std::string>& choices) const;

  // Reports the first key that no accessor read. Call after reading everything.
  void finish() const;

 private:
  const nlohmann::json& at(const std::string& key) const;
  const nlohmann::json* value_;
  std::string file_, path_;
  mutable std::set<std::string> used_;
};

// "number", "string", ... for messages.
std::string json_type_name(const nlohmann::json& value);

}  // namespace countershade
