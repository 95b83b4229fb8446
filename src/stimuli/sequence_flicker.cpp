#include "stimuli/sequence_flicker.h"

#include <map>
#include <memory>

#include <tbb/parallel_for.h>

#include "core/number_format.h"
#include "core/parallel.h"
#include "enhance/lightness.h"
#include "render/ray_tracer.h"
#include "render/renderer.h"
#include "render/scene_animation.h"
#include "stimuli/perspective_coherence.h"

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

// A frame's geometry as a View without pixels: what the reprojection reads.
std::shared_ptr<const View> geometry_view(std::shared_ptr<const Scene> scene, int threads) {
  auto view = std::make_shared<View>();
  const RayTracer tracer(*scene);
  view->render.gbuffer = render_gbuffer(*scene, tracer, threads);
  view->depth = view->render.gbuffer.depth;
  view->display = Image(scene->camera.width, scene->camera.height, 1);
  view->scene = std::move(scene);
  return view;
}

struct FrameLayers {
  std::shared_ptr<const View> geometry;
  std::map<std::string, std::vector<float>> layers;  // sequence folder → its layer at this frame
};

class FlickerMeter {
 public:
  FlickerMeter(const Experiment& e, const fs::path& dir, const ExperimentScene& scene, const Scene& base, int threads)
      : e_(e), dir_(dir), base_(base), threads_(threads), reference_(scene.name + "/reference") {}

  void measure(Sequences& sequences) const;

 private:
  std::vector<float> lightness(const ManifestEntry& entry) const;
  FrameLayers layers_at(const Sequences& sequences, int frame) const;
  void measure_pair(Sequences& sequences, const FrameLayers& previous, const FrameLayers& current, int frame) const;

  const Experiment& e_;
  fs::path dir_;
  const Scene& base_;
  int threads_;
  std::string reference_;
};

std::vector<float> FlickerMeter::lightness(const ManifestEntry& entry) const {
  const LabPixels lab = display_to_lab(read_image(dir_ / entry.file), base_.display.encoding, e_.bits);
  std::vector<float> l(lab.size());
  for (size_t i = 0; i < l.size(); ++i) l[i] = float(lab[i].L);
  return l;
}

FrameLayers FlickerMeter::layers_at(const Sequences& sequences, int frame) const {
  FrameLayers out;
  out.geometry = geometry_view(std::make_shared<const Scene>(scene_at(base_, base_.animation->time_of(frame))), threads_);
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
  return out;
}

// One frame pair of every sequence that has both frames. The reference's own per-pixel change
// comes first: it picks the stable pixels of every condition.
void FlickerMeter::measure_pair(Sequences& sequences, const FrameLayers& previous, const FrameLayers& current,
                                int frame) const {
  const CarryPoint carry = carry_between_frames(base_, frame - 1, frame);
  auto record = [&](const std::string& folder, std::vector<float>& differences) {
    const Reprojection r = reprojection_rms(*previous.geometry, previous.layers.at(folder), *current.geometry,
                                            current.layers.at(folder), carry, &differences);
    ManifestEntry& entry = *sequences.at(folder).at(frame);
    entry.extra["flicker"] = round_to(r.rms, 4);
    entry.extra["flicker_pixels"] = r.pixels;
    return &entry;
  };
  std::vector<float> plain;
  std::vector<std::string> folders;
  for (const auto& [folder, layer] : current.layers) {
    if (!previous.layers.count(folder)) continue;
    if (folder == reference_) record(folder, plain);  // before the others: it picks their stable pixels
    else folders.push_back(folder);
  }
  parallel_ranges(folders.size(), threads_, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      std::vector<float> differences;
      ManifestEntry* entry = record(folders[k], differences);
      if (plain.empty()) continue;
      const Reprojection stable = rms_where_stable(differences, plain, kStableTolerance);
      entry->extra["flicker_stable"] = round_to(stable.rms, 4);
      entry->extra["flicker_stable_pixels"] = stable.pixels;
    }
  });
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

void measure_sequence_flicker(const Experiment& e, const fs::path& dir, const ExperimentScene& scene, const Scene& base,
                              std::vector<ManifestEntry>& entries, int threads) {
  Sequences sequences = sequences_of(scene.name, entries);
  if (!sequences.empty() && base.animation) FlickerMeter(e, dir, scene, base, threads).measure(sequences);
}

}  // namespace countershade
