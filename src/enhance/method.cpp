#include "enhance/method.h"

#include "enhance/none.h"
#include "enhance/usm3d.h"

namespace countershade {

View make_view(const Scene& scene, RenderResult render) {
  View view;
  view.scene = &scene;
  view.display = encode_for_display(render.radiance, scene.display);
  view.lab = display_to_lab(view.display, scene.display.encoding);
  view.render = std::move(render);
  return view;
}

namespace {

// The registry: one entry per method.
const std::vector<const EnhancementMethod*>& registry() {
  static const NoEnhancement none;
  static const Usm3dMethod usm3d;
  static const std::vector<const EnhancementMethod*> methods = {&none, &usm3d};
  return methods;
}

}  // namespace

const EnhancementMethod* find_method(const std::string& name) {
  for (const EnhancementMethod* m : registry())
    if (m->name() == name) return m;
  return nullptr;
}

std::vector<std::string> method_names() {
  std::vector<std::string> names;
  for (const EnhancementMethod* m : registry()) names.push_back(m->name());
  return names;
}

}  // namespace countershade
