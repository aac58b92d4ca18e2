// The opaque StratumScene handle of the C ABI: one definition, shared by every file that reads
// it (scene_api.cpp, texture_api.cpp; renderer_api.cpp makes renderers of it). The scene lives
// in a LiveScene shared with the renderers made from it, so that edits reach them.
#pragma once

#include <memory>

#include "scene/live_scene.h"

struct StratumScene {
    std::shared_ptr<stratum::LiveScene> live = std::make_shared<stratum::LiveScene>();
};
