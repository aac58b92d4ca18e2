// Which model builds each light type (the C ABI's StratumLightType value): one line per type in
// light_registry.cpp, with the value, the name hosts look it up by, and the LightModel the light's
// own file defines (lights/light.h). Adding a light type is described in docs/adding_models.md.
#pragma once

#include <cstdint>
#include <memory>

#include "core/model_table.h"
#include "lights/light.h"
#include "scene/scene.h"

namespace stratum {

// Types are numbered 0 .. kMaxLightTypes − 1.
inline constexpr int32_t kMaxLightTypes = 32;
using LightModels = ModelTable<LightModel, kMaxLightTypes>;

// Every registered light type, in value order (what stratum_model_* list).
const LightModels& light_models();
// The model registered for `type`, or null (how the C ABI tells a light type it knows).
const LightModel* find_light_model(int32_t type);
// The light `params` describe; throws std::runtime_error when no model is registered for its type.
std::unique_ptr<Light> make_light(const LightParams& params);
// Registers `model` (kept by address: a static) for a type that has none, under `name` (a
// static string): how a test adds a light type of its own. Call it before any scene that uses
// the type is validated or built, and not while another thread reads the registry. False when
// the type is out of range or taken.
bool register_light_model(int32_t type, const char* name, const LightModel& model);

}  // namespace stratum
