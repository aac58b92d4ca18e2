// Captured scenes: the whole scene as one JSON file, for the native CLI, benchmarks and bug
// reports. Loading goes through the public C entry points, so a file is validated exactly as
// the add-on's calls are.
#pragma once

#include <string>

#include "scene/scene.h"
#include "stratum/stratum.h"

namespace stratum {

// Returns "" on success, else the error.
std::string save_scene_file(const Scene& scene, const char* path);
// Fills `scene` (fresh) from the file; on failure `error` says why.
StratumStatus load_scene_file(const char* path, StratumScene* scene, std::string* error);

}  // namespace stratum
