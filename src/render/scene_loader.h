#pragma once
// Scene files (docs/scene-format.md): every key read and checked, errors naming the file and the
// field; meshes, textures and objects loaded, the objects' surface graphs built on request.

#include <filesystem>

#include "render/scene.h"

namespace countershade {

class JsonObject;

// With `surface_graphs`, each object's welded surface (Object::surface) is built as well: the
// vertex signal and the methods that work on mesh surfaces need it; a plain render does not.
Scene load_scene(const std::filesystem::path& path, bool surface_graphs = true);

// A "noise" object: target, p99, min_spp, max_spp, time_limit (scene and experiment files).
NoiseBudget read_noise_budget(const JsonObject& o);

}  // namespace countershade
