// The opaque StratumScene handle of the C ABI: one definition, shared by every file that
// implements scene entry points (stratum_api.cpp, texture_api.cpp).
#pragma once

#include "scene/scene.h"

struct StratumScene {
    stratum::Scene scene;
};
