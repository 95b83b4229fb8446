// Fuzzes the scene JSON reader (render/scene): any bytes as a scene file, next to a mesh.obj and a
// texture.png it may use.
#include "core/image.h"
#include "fuzz/fuzz_input.h"
#include "render/scene.h"
#include "render/scene_loader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool support = [] {
    countershade::fuzz::write_support_file("mesh.obj", countershade::fuzz::kSupportMesh);
    countershade::Image texture(2, 2, 3);
    for (size_t i = 0; i < texture.pixels.size(); ++i) texture.pixels[i] = float(i) / 12.0f;
    countershade::write_image(countershade::fuzz::input_folder() / "texture.png", texture);
    return true;
  }();
  (void)support;
  const auto path = countershade::fuzz::write_input(data, size, "scene.json");
  return countershade::fuzz::expect_clean_refusal([&] { countershade::load_scene(path); });
}
