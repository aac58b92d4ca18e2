// The shader programs, their bindings (closure parameters, lamps) and the meshes' texture spaces
// in a captured scene file (api/scene_file.h): saved from the Scene, loaded through the public
// entry points.
#pragma once

#include <nlohmann/json.hpp>

#include "scene/scene.h"
#include "stratum/stratum.h"

namespace stratum {

void save_programs(const Scene& scene, nlohmann::json& file);
// After the file's materials, meshes and textures are loaded. `version` is the file's: a
// version 1 file was written when the renderer's inputs took the first 100 registers, a version
// 2 file when they took 128, so its programs' own registers (and every register number at or
// above that count) move up to follow the 144 of today.
StratumStatus load_programs(const nlohmann::json& file, StratumScene* scene, int version);

}  // namespace stratum
