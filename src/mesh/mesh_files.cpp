#include "mesh/mesh_files.h"

#include <tbb/parallel_for_each.h>

#include "core/error.h"
#include "mesh/mesh_io.h"

namespace countershade {

MeshFiles::MeshFiles(const std::vector<std::filesystem::path>& paths) {
  for (const auto& path : paths) ++files_[path].takes_left;
  std::vector<std::pair<const std::filesystem::path, Loaded>*> work;
  for (auto& entry : files_) work.push_back(&entry);
  tbb::parallel_for_each(work.begin(), work.end(), [](auto* entry) {
    try {
      entry->second.mesh = load_mesh(entry->first);
    } catch (const InputError& e) {
      entry->second.error = e.what();
    }
  });
}

TriangleMesh MeshFiles::take(const std::filesystem::path& path) {
  const auto found = files_.find(path);
  if (found == files_.end()) return load_mesh(path);
  Loaded& loaded = found->second;
  if (!loaded.error.empty()) throw InputError(loaded.error);
  if (loaded.takes_left == 0) return load_mesh(path);  // taken more often than named
  return --loaded.takes_left > 0 ? loaded.mesh : std::move(loaded.mesh);
}

}  // namespace countershade
