#include "stimuli/manifest.h"

#include <fstream>
#include <set>

#include "core/error.h"
#include "core/json_reader.h"
#include "core/sha256.h"

namespace countershade {

std::filesystem::path resolve_in_set(const std::filesystem::path& set_dir, const std::string& relative) {
  std::filesystem::path p(relative);
  if (relative.empty() || p.is_absolute()) throw InputError("path '" + relative + "' must be relative to the set folder");
  for (const auto& part : p)
    if (part == "..") throw InputError("path '" + relative + "' leaves the set folder");
  return set_dir / p;
}

OrderedJson read_manifest(const std::filesystem::path& path) {
  parse_json_file(path);  // the file exists and is valid JSON (errors name the file)
  std::ifstream in(path, std::ios::binary);
  OrderedJson manifest = OrderedJson::parse(in);  // keeps the keys in the order they were written
  auto fail = [&](const std::string& field, const std::string& what) { throw_input_error(path.string() + ": " + field, what); };
  if (!manifest.is_object()) fail("", "expected an object");
  if (!manifest.contains("format_version") || manifest["format_version"] != kManifestFormatVersion)
    fail("format_version", "missing or unsupported (expected " + std::to_string(kManifestFormatVersion) + ")");
  if (!manifest.contains("stimuli") || !manifest["stimuli"].is_array()) fail("stimuli", "missing or not an array");
  for (size_t i = 0; i < manifest["stimuli"].size(); ++i) {
    const auto& s = manifest["stimuli"][i];
    std::string where = "stimuli[" + std::to_string(i) + "]";
    for (const char* key : {"file", "scene", "method", "sha256"})
      if (!s.contains(key) || !s[key].is_string()) fail(where + "." + key, "missing or not a string");
    for (const char* key : {"width", "height"})
      if (!s.contains(key) || !s[key].is_number_integer()) fail(where + "." + key, "missing or not an integer");
    try {
      resolve_in_set(path.parent_path(), s["file"].get<std::string>());
    } catch (const InputError& e) {
      fail(where + ".file", e.what());
    }
  }
  return manifest;
}

std::vector<std::string> verify_stimulus_set(const std::filesystem::path& manifest_path) {
  OrderedJson manifest = read_manifest(manifest_path);
  const auto dir = manifest_path.parent_path();
  std::vector<std::string> problems;
  std::set<std::filesystem::path> listed;
  for (const auto& s : manifest["stimuli"]) {
    auto file = resolve_in_set(dir, s["file"].get<std::string>());
    listed.insert(std::filesystem::weakly_canonical(file));
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) {
      problems.push_back(s["file"].get<std::string>() + ": missing");
      continue;
    }
    if (s.contains("size") && std::filesystem::file_size(file) != s["size"].get<uintmax_t>())
      problems.push_back(s["file"].get<std::string>() + ": size differs from the manifest");
    if (sha256_file(file) != s["sha256"].get<std::string>())
      problems.push_back(s["file"].get<std::string>() + ": sha256 differs from the manifest");
  }
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file() || entry.path().extension() != ".png") continue;
    auto rel = std::filesystem::relative(entry.path(), dir).string();
    if (rel.rfind("contact-sheets", 0) == 0) continue;
    if (!listed.count(std::filesystem::weakly_canonical(entry.path()))) problems.push_back(rel + ": not in the manifest");
  }
  return problems;
}

OrderedJson reproducible_part(const OrderedJson& manifest) {
  OrderedJson copy = manifest;
  copy.erase("run");
  return copy;
}

}  // namespace countershade
