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

// The library's object, or none with why in `why`. A library built for another interface (left
// from another build or install) is closed before the program calls into it.
void* open_plugin(const fs::path& place, const std::string& name, std::string& why) {
  void* library = dlopen(place.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!library) {
    const char* error = dlerror();
    why = error ? error : place.string();
    return nullptr;
  }
  using Stamp = const char* (*)();
  const auto stamp = reinterpret_cast<Stamp>(dlsym(library, "countershade_plugin_interface"));
  const std::string interface = stamp ? stamp() : "(no stamp)";
  if (interface != COUNTERSHADE_PLUGIN_INTERFACE) {
    why = place.string() + ": built for another version of countershade (interface " + interface +
          ", this program's " + COUNTERSHADE_PLUGIN_INTERFACE +
          "); install the program and its libraries together";
    dlclose(library);
    return nullptr;
  }
  using Entry = void* (*)();
  const auto entry = reinterpret_cast<Entry>(dlsym(library, ("countershade_" + name).c_str()));
  if (!entry) throw std::runtime_error(place.string() + ": no entry point countershade_" + name);
  return entry();
}

void* load(const std::string& name) {
  const std::string file = "libcountershade_" + name + ".so";
  std::string tried;
  for (const fs::path& place : places(file)) {
    std::string why;
    if (void* object = open_plugin(place, name, why)) return object;
    tried += (tried.empty() ? "" : "; ") + why;
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
