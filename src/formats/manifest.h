#pragma once
// The manifest of a stimulus set (docs/data-formats): what every file is, how it was made, and
// its checksum. The one owner of the format: the generator writes it, the app, the audit and
// the tests read it. Paths are relative to the set folder and may not leave it.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace countershade {

using OrderedJson = nlohmann::ordered_json;

inline constexpr int kManifestFormatVersion = 1;
// The `method` of a scene's reference (unenhanced) image.
inline constexpr const char* kReferenceMethod = "none";

struct LambdaGridInfo {
  double min = 0, max = 0, step = 0;
  int count = 0;
};

struct ManifestEntry {
  std::string file;  // relative to the set folder
  std::string scene, method;
  std::string label;            // the method's folder name; empty for references
  std::optional<double> sigma;  // absent for references
  std::string sigma_kind;       // the width key the σ list was given under
  double lambda = 0;
  int lambda_index = 0;
  uint64_t clipped_pixels = 0;
  // A frame of a sequence: its index in the scene's animation, and the sequence's frame rate. The
  // sequence is the entry's folder; its frames are the entries there (absent for a still).
  struct Frame {
    int index = 0;
    double fps = 0;
  };
  std::optional<Frame> frame;
  OrderedJson extra =
      OrderedJson::object();  // method details: parameters, operator, iterations, noise, ...
  int width = 0, height = 0;
  uint64_t size = 0;
  std::string sha256;

  // The reference has no label; the method `none` in an experiment has one (a control condition).
  bool is_reference() const { return method == kReferenceMethod && label.empty(); }
  // The folder of the sequence a frame belongs to (the folder of its file).
  std::string sequence() const { return std::filesystem::path(file).parent_path().string(); }
  // The condition's name in studies: the label, or the method when there is none.
  const std::string& condition_method() const { return label.empty() ? method : label; }
};

// The sampling noise recorded for an image (entry.extra["noise"], docs/stimulus-sets.md): the
// estimate in L* and, for images sampled to a budget, the budget and whether it was met.
struct ImageNoise {
  double rms = 0, p99 = 0;
  struct Budget {
    double target = 0, p99 = 0;
    bool met = false;
  };
  std::optional<Budget> budget;
};
void set_image_noise(ManifestEntry& entry, const ImageNoise& noise);
std::optional<ImageNoise> image_noise(const ManifestEntry& entry);  // none when not recorded

// How a set is to be viewed (docs/display.md): the experiment's screen and its pixels per degree.
// (A scene shown on a calibrated display records its lookup table and luminance range on its
// reference entry: `display_lut`, `luminance_cd_m2`.)
struct Viewing {
  std::optional<double> pixels_per_degree;
  double width_mm = 0, distance_mm = 0;  // the screen's
  int width_px = 0;
  bool empty() const { return !pixels_per_degree; }
};

struct Manifest {
  int format_version = kManifestFormatVersion;
  std::string software_version, experiment_name, experiment_sha256;
  OrderedJson experiment = OrderedJson::object();  // the experiment file as read
  uint64_t seed = 1;
  int bits = 8;
  LambdaGridInfo lambda_grid;
  std::optional<std::pair<int, int>> shard;  // index, count
  std::vector<ManifestEntry> stimuli;
  // Lossless videos of the sequences, for sharing: {file, sequence, frames, fps, size, sha256}.
  OrderedJson videos = OrderedJson::array();
  Viewing viewing;  // "viewing", when the experiment gives a screen or a scene a calibrated display
  OrderedJson run = OrderedJson::object();  // timings and timestamps: differ between runs
  std::string file_sha256;                  // of the file it was read from (not written)
};

OrderedJson to_json(const ManifestEntry& entry);
OrderedJson to_json(const Manifest& manifest);

// One entry from its JSON (e.g. a journal line); `file` and `index` name it in messages.
ManifestEntry parse_manifest_entry(const OrderedJson& json, const std::filesystem::path& file,
                                   size_t index);

// Reads a manifest and checks its structure; throws InputError naming the file and the field.
Manifest read_manifest(const std::filesystem::path& path);
// Writes it atomically.
void write_manifest(const std::filesystem::path& path, const Manifest& manifest);

// Joins a manifest's relative path to its folder; rejects absolute paths and paths that leave it.
std::filesystem::path resolve_in_set(const std::filesystem::path& set_dir,
                                     const std::string& relative);

// Checks a finished set: every listed file exists with its size and sha256, and every PNG in the
// folder is listed. Returns the problems found (empty when the set is intact).
std::vector<std::string> verify_stimulus_set(const std::filesystem::path& manifest_path);

// read_manifest of a set whose files all match it (verify_stimulus_set); an InputError names the
// first mismatch.
Manifest read_verified_manifest(const std::filesystem::path& manifest_path);

// The manifest without the fields that legitimately differ between runs (timings, timestamps).
OrderedJson reproducible_part(const Manifest& manifest);

// Sorts entries by file name, the order a manifest lists them in.
void sort_entries(std::vector<ManifestEntry>& entries);

}  // namespace countershade
