#include "enhance/registry.h"

#include "core/error.h"
#include "core/named_registry.h"

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

NamedRegistry<EnhancementMethod>& registry() {
  // Never destroyed: registrations may run during static destruction.
  static auto* r = [] {
    std::vector<std::unique_ptr<const EnhancementMethod>> builtins;
#define COUNTERSHADE_ADD_BUILTIN(id) builtins.push_back(make_##id##_method());
    COUNTERSHADE_BUILTIN_METHODS(COUNTERSHADE_ADD_BUILTIN)
    return new NamedRegistry<EnhancementMethod>(std::move(builtins));
  }();
  return *r;
}

}  // namespace

void register_method(std::unique_ptr<const EnhancementMethod> method) {
  registry().add(std::move(method), "method");
}

const EnhancementMethod* find_method(const std::string& name) { return registry().find(name); }

std::vector<std::string> method_names() { return registry().names(); }

// The first built-in.
const EnhancementMethod& unenhanced_method() { return registry().first(); }

const EnhancementMethod& method_named(const std::string& name, const std::string& where) {
  if (const EnhancementMethod* m = find_method(name)) return *m;
  std::string list;
  for (const auto& n : method_names()) list += (list.empty() ? "" : ", ") + n;
  throw_input_error(where, "unknown method '" + name + "' (methods: " + list + ")");
}

}  // namespace countershade
