#include "core/plugin_library.h"

#include <dlfcn.h>

#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace countershade {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> places(const std::string& file) {
  std::error_code ec;
  const fs::path program = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return {file};  // the dynamic loader's own search
  const fs::path folder = program.parent_path();
  return {folder / file, folder.parent_path() / "lib" / "countershade" / file};
}

void* load(const std::string& name) {
  const std::string file = "libcountershade_" + name + ".so";
  std::string tried;
  for (const fs::path& place : places(file)) {
    void* library = dlopen(place.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!library) {
      const char* why = dlerror();
      tried += (tried.empty() ? "" : "; ") + std::string(why ? why : place.string());
      continue;
    }
    using Entry = void* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(library, ("countershade_" + name).c_str()));
    if (!entry) throw std::runtime_error(place.string() + ": no entry point countershade_" + name);
    return entry();
  }
  throw std::runtime_error("cannot load " + file + " (" + tried + ")");
}

}  // namespace

void* plugin_object(const std::string& name) {
  static std::mutex mutex;
  static std::map<std::string, void*> loaded;
  const std::lock_guard<std::mutex> lock(mutex);
  void*& object = loaded[name];
  if (!object) object = load(name);
  return object;
}

}  // namespace countershade
