#include "stimuli/sequence_flicker.h"

#include <tbb/parallel_for.h>

#include <map>
#include <memory>

#include "core/number_format.h"
#include "core/parallel.h"
#include "enhance/lightness.h"
#include "measures/flicker.h"
#include "render/scene_animation.h"
#include "stimuli/mask_file.h"

namespace countershade {
namespace fs = std::filesystem;
namespace {

// Sequence folder → frame → its entry.
using Sequences = std::map<std::string, std::map<int, ManifestEntry*>>;

Sequences sequences_of(const std::string& scene, std::vector<ManifestEntry>& entries) {
  Sequences out;
  for (ManifestEntry& s : entries)
    if (s.scene == scene && s.frame) out[s.sequence()][s.frame->index] = &s;
  return out;
}

struct FrameLayers {
  std::shared_ptr<const View> geometry;
  std::map<std::string, std::vector<float>> layers;  // sequence folder → its layer at this frame
  std::map<std::string, std::vector<float>> masks;  // mask file → the mask (one per method and σ)
};

// The mask file a sequence's frame names (empty: none).
std::string mask_of(const ManifestEntry& entry) {
  return entry.extra.contains("mask") ? entry.extra["mask"]["file"].get<std::string>()
                                      : std::string();
}

class FlickerMeter {
 public:
  FlickerMeter(const Experiment& e, const fs::path& dir, const ExperimentScene& scene,
               const Scene& base, int threads)
      : e_(e), dir_(dir), base_(base), threads_(threads), reference_(scene.name + "/reference") {}

  void measure(Sequences& sequences) const;

 private:
  std::vector<float> lightness(const ManifestEntry& entry) const;
  FrameLayers layers_at(const Sequences& sequences, int frame) const;
  void measure_pair(Sequences& sequences, const FrameLayers& previous, const FrameLayers& current,
                    int frame) const;
  void record_mask_flicker(Sequences& sequences, const std::vector<std::string>& folders,
                           const FrameLayers& previous, const FrameLayers& current,
                           const CarryPoint& carry, int frame) const;

  const Experiment& e_;
  fs::path dir_;
  const Scene& base_;
  int threads_;
  std::string reference_;
};

std::vector<float> FlickerMeter::lightness(const ManifestEntry& entry) const {
  const LabPixels lab =
      display_to_lab(read_image(dir_ / entry.file), base_.display.encoding, e_.bits);
  std::vector<float> l(lab.size());
  for (size_t i = 0; i < l.size(); ++i) l[i] = float(lab[i].L);
  return l;
}

FrameLayers FlickerMeter::layers_at(const Sequences& sequences, int frame) const {
  FrameLayers out;
  out.geometry = geometry_view(
      std::make_shared<const Scene>(scene_at(base_, base_.animation->time_of(frame))), threads_);
  const auto references = sequences.find(reference_);
  if (references == sequences.end() || !references->second.count(frame)) return out;
  const std::vector<float> plain = lightness(*references->second.at(frame));
  std::vector<std::string> folders;
  for (const auto& [folder, frames] : sequences)
    if (frames.count(frame)) folders.push_back(folder);
  std::vector<std::vector<float>> layers(folders.size());
  parallel_ranges(folders.size(), threads_, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      if (folders[k] == reference_) {
        layers[k] = plain;
        continue;
      }
      layers[k] = lightness(*sequences.at(folders[k]).at(frame));
      for (size_t i = 0; i < plain.size(); ++i) layers[k][i] -= plain[i];
    }
  });
  for (size_t k = 0; k < folders.size(); ++k) out.layers[folders[k]] = std::move(layers[k]);
  for (const std::string& folder : folders)
    if (const std::string mask = mask_of(*sequences.at(folder).at(frame));
        !mask.empty() && !out.masks.count(mask))
      out.masks[mask] = read_mask(dir_ / mask);
  return out;
}

// One frame pair of every sequence that has both frames, measured as the `flicker` command
// measures it (stimuli/flicker.h). The reference's own change is the plain change; its per-pixel
// differences pick the stable pixels of every condition.
void FlickerMeter::measure_pair(Sequences& sequences, const FrameLayers& previous,
                                const FrameLayers& current, int frame) const {
  const auto plain_a = previous.layers.find(reference_), plain_b = current.layers.find(reference_);
  if (plain_a == previous.layers.end() || plain_b == current.layers.end()) return;
  const auto frame_of = [&](const FrameLayers& layers, const std::vector<float>& layer,
                            const std::vector<float>& plain) {
    FlickerFrame f;
    f.view = layers.geometry;
    f.layer = layer;
    f.plain = plain;
    return f;
  };
  const CarryPoint carry = carry_between_frames(base_, frame - 1, frame);
  const PlainChange plain =
      plain_change(frame_of(previous, plain_a->second, plain_a->second),
                   frame_of(current, plain_b->second, plain_b->second), carry);
  const auto record = [&](const std::string& folder, const Reprojection& r) {
    ManifestEntry& entry = *sequences.at(folder).at(frame);
    entry.extra["flicker"] = round_to(r.rms, 4);
    entry.extra["flicker_pixels"] = r.pixels;
    return &entry;
  };
  record(reference_, plain.rms);
  std::vector<std::string> folders;
  for (const auto& [folder, layer] : current.layers)
    if (folder != reference_ && previous.layers.count(folder)) folders.push_back(folder);
  record_mask_flicker(sequences, folders, previous, current, carry, frame);
  FlickerOptions options;
  options.stable = kStableTolerance;
  parallel_ranges(folders.size(), threads_, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      const PairFlicker pair = pair_flicker(
          frame_of(previous, previous.layers.at(folders[k]), plain_a->second),
          frame_of(current, current.layers.at(folders[k]), plain_b->second), carry, plain, options);
      ManifestEntry* entry = record(folders[k], pair.layer);
      entry->extra["flicker_stable"] = round_to(pair.stable.rms, 4);
      entry->extra["flicker_stable_pixels"] = pair.stable.pixels;
    }
  });
}

// The mask flicker of every condition that has a mask in both frames: the reprojection of the
// flicker applied to the mask (docs/enhancement-methods.md, "Mask flicker"), measured once per
// method and σ and recorded in each of its λ's entries.
void FlickerMeter::record_mask_flicker(Sequences& sequences,
                                       const std::vector<std::string>& folders,
                                       const FrameLayers& previous, const FrameLayers& current,
                                       const CarryPoint& carry, int frame) const {
  std::map<std::string, Reprojection> measured;  // mask file of this frame → its change
  for (const std::string& folder : folders) {
    ManifestEntry& entry = *sequences.at(folder).at(frame);
    const std::string mask = mask_of(entry), before = mask_of(*sequences.at(folder).at(frame - 1));
    if (mask.empty() || before.empty()) continue;
    if (!measured.count(mask))
      measured[mask] = reprojection_rms(*previous.geometry, previous.masks.at(before),
                                        *current.geometry, current.masks.at(mask), carry);
    entry.extra["mask_flicker"] = round_to(measured[mask].rms, 4);
    entry.extra["mask_flicker_pixels"] = measured[mask].pixels;
  }
}

void FlickerMeter::measure(Sequences& sequences) const {
  int first = 1 << 30, last = -1;
  for (const auto& [folder, frames] : sequences) {
    first = std::min(first, frames.begin()->first);
    last = std::max(last, frames.rbegin()->first);
  }
  FrameLayers previous = layers_at(sequences, first);
  for (int f = first + 1; f <= last; ++f) {
    FrameLayers current = layers_at(sequences, f);
    measure_pair(sequences, previous, current, f);
    previous = std::move(current);
  }
}

}  // namespace

void measure_sequence_flicker(const Experiment& e, const fs::path& dir,
                              const ExperimentScene& scene, const Scene& base,
                              std::vector<ManifestEntry>& entries, int threads) {
  Sequences sequences = sequences_of(scene.name, entries);
  if (!sequences.empty() && base.animation)
    FlickerMeter(e, dir, scene, base, threads).measure(sequences);
}

}  // namespace countershade
