// The shader programs, their bindings and the meshes' texture spaces in a captured scene file
// (api/scene_file.h): saved from the Scene, loaded through the public entry points.
#pragma once

#include <nlohmann/json.hpp>

#include "scene/scene.h"
#include "stratum/stratum.h"

namespace stratum {

void save_programs(const Scene& scene, nlohmann::json& file);
// After the file's materials, meshes and textures are loaded.
StratumStatus load_programs(const nlohmann::json& file, StratumScene* scene);

}  // namespace stratum
