#pragma once
// The manifest of a stimulus set (docs/data-formats): what every file is, how it was made, and
// its checksum. Paths are relative to the set folder and may not leave it.

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace countershade {

using OrderedJson = nlohmann::ordered_json;

inline constexpr int kManifestFormatVersion = 1;

// Reads a manifest and checks its structure; throws InputError naming the file and the field.
OrderedJson read_manifest(const std::filesystem::path& path);

// Joins a manifest's relative path to its folder; rejects absolute paths and paths that leave it.
std::filesystem::path resolve_in_set(const std::filesystem::path& set_dir, const std::string& relative);

// Checks a finished set: every listed file exists with its size and sha256, and every PNG in the
// folder is listed. Returns the problems found (empty when the set is intact).
std::vector<std::string> verify_stimulus_set(const std::filesystem::path& manifest_path);

// The manifest without the fields that legitimately differ between runs (timings, timestamps).
OrderedJson reproducible_part(const OrderedJson& manifest);

}  // namespace countershade
