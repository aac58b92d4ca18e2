// A material parameter driven by an image texture (stratum_scene_bind_texture), as stored in
// the Scene. Kept apart from material_texturing.h so scene/scene.h can hold bindings without
// depending on the code that applies them.
#pragma once

#include <cstdint>

namespace stratum {

// Mirrors StratumMaterialParam.
enum class MaterialParam : int32_t {
    BaseColor = 0,
    Roughness = 1,
    Metallic = 2,
    Normal = 3,
    Emission = 4,
    Weight = 5,
    Transmission = 6,
    Specular = 7
};

struct TextureBinding {
    uint32_t material_id = 0;
    uint32_t closure_index = 0;
    MaterialParam param = MaterialParam::BaseColor;
    uint32_t texture_id = 0;
    int32_t channel = -1;  // -1 RGB, 0..3 one channel replicated
    float scale = 1.0f;    // Normal: the Normal Map node's strength
    float offset = 0.0f;
};

}  // namespace stratum
