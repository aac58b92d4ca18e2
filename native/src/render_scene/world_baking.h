// The world's node program baked into an equirectangular environment image, which the
// renderer then looks up and importance-samples as any environment (lights/environment_light.h).
// A program that reads the Light Path node is baked with Cycles' importance-map state (no ray
// kind, Ray Depth 1) and runs again for each ray (lights/world_program.h).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "lights/world_program.h"
#include "scene/scene.h"
#include "shading/shader_program.h"

namespace stratum {

// Each texel is the mean of the program's RGB at register `color` over 2 x 2 directions spread
// over the texel (rows top (+Z) to bottom, the environment's mapping); a value that is NaN,
// infinite or negative counts 0, as environment pixels do. Texels near a sharp feature (the
// brightest sample of the texel and its 8 neighbours over 8 times the dimmest: a sun disc) are
// integrated again over 16 x 16 directions weighted by solid angle, which keeps a disc's
// irradiance to ~0.1% where 2 x 2 samples were off by up to ~10%.
Environment bake_environment(const ShaderProgram& program,
                             const std::vector<std::shared_ptr<const Texture>>& textures, uint32_t color,
                             uint32_t width, uint32_t height);

}  // namespace stratum
