#include "enhance/registry.h"

#include <mutex>
#include <stdexcept>

#include "core/error.h"

namespace countershade {

// The built-in methods, one line each. Every method file defines its factory.
#define COUNTERSHADE_BUILTIN_METHODS(X) \
  X(none)                               \
  X(usm3d)                              \
  X(usm2d)                              \
  X(depth_usm)                          \
  X(cornsweet)                          \
  X(lla)                                \
  X(exaggerated_shading)                \
  X(radiance_scaling)                   \
  X(light_warping)                      \
  X(texture_filter)

#define COUNTERSHADE_DECLARE_FACTORY(id) \
  std::unique_ptr<const EnhancementMethod> make_##id##_method();
COUNTERSHADE_BUILTIN_METHODS(COUNTERSHADE_DECLARE_FACTORY)

namespace {

struct Registry {
  std::mutex mutex;
  std::vector<std::unique_ptr<const EnhancementMethod>> methods;
};

Registry& registry() {
  static Registry* r = [] {
    auto* reg = new Registry;  // never destroyed: registrations may run during static destruction
#define COUNTERSHADE_ADD_BUILTIN(id) reg->methods.push_back(make_##id##_method());
    COUNTERSHADE_BUILTIN_METHODS(COUNTERSHADE_ADD_BUILTIN)
    return reg;
  }();
  return *r;
}

}  // namespace

void register_method(std::unique_ptr<const EnhancementMethod> method) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  for (const auto& m : r.methods)
    if (m->name() == method->name())
      throw std::logic_error("method '" + method->name() + "' is registered twice");
  r.methods.push_back(std::move(method));
}

const EnhancementMethod* find_method(const std::string& name) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  for (const auto& m : r.methods)
    if (m->name() == name) return m.get();
  return nullptr;
}

std::vector<std::string> method_names() {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  std::vector<std::string> names;
  for (const auto& m : r.methods) names.push_back(m->name());
  return names;
}

const EnhancementMethod& unenhanced_method() {
  Registry& r = registry();
  std::lock_guard<std::mutex> lock(r.mutex);
  return *r.methods.front();  // the first built-in
}

const EnhancementMethod& method_named(const std::string& name, const std::string& where) {
  if (const EnhancementMethod* m = find_method(name)) return *m;
  std::string list;
  for (const auto& n : method_names()) list += (list.empty() ? "" : ", ") + n;
  throw_input_error(where, "unknown method '" + name + "' (methods: " + list + ")");
}

}  // namespace countershade
