#include "stimuli/sequence_videos.h"

#include <algorithm>
#include <map>

#include "core/parallel.h"
#include "core/sha256.h"
#include "stimuli/lossless_video.h"

namespace countershade {
namespace fs = std::filesystem;

void write_sequence_videos(const fs::path& dir, Manifest& manifest, int threads) {
  std::map<std::string, std::vector<const ManifestEntry*>> sequences;  // folder → its frames
  for (const ManifestEntry& s : manifest.stimuli)
    if (s.frame) sequences[s.sequence()].push_back(&s);
  std::vector<std::string> folders;
  for (auto& [folder, frames] : sequences) {
    std::sort(frames.begin(), frames.end(),
              [](auto* a, auto* b) { return a->frame->index < b->frame->index; });
    folders.push_back(folder);
  }
  std::vector<OrderedJson> videos(folders.size());
  parallel_ranges(folders.size(), threads, [&](size_t begin, size_t end) {
    for (size_t k = begin; k < end; ++k) {
      const auto& entries = sequences.at(folders[k]);
      std::vector<Image> frames;
      for (const ManifestEntry* s : entries)
        frames.push_back(read_image(resolve_in_set(dir, s->file)));
      const std::string file = folders[k] + ".mkv";
      write_lossless_video(dir / file, frames, entries.front()->frame->fps);
      videos[k] = {{"file", file},
                   {"sequence", folders[k]},
                   {"frames", frames.size()},
                   {"fps", entries.front()->frame->fps},
                   {"size", fs::file_size(dir / file)},
                   {"sha256", sha256_file(dir / file)}};
    }
  });
  manifest.videos = OrderedJson::array();
  for (auto& v : videos) manifest.videos.push_back(std::move(v));
}

}  // namespace countershade
