// Validation of the texture entry points' descriptions (stratum_scene_add_texture,
// stratum_scene_bind_texture): every field is checked and a bad one named in a
// ValidationError; a file that cannot be read is an ImageReadError (STRATUM_ERROR_IO).
#pragma once

#include <memory>

#include "scene/scene.h"
#include "stratum/stratum.h"
#include "texture/texture.h"
#include "texture/texture_binding.h"

namespace stratum {

// Checks `desc`, reads its image and converts it to scene linear.
std::shared_ptr<const Texture> load_texture(const StratumTextureDesc& desc);

// Checks `desc` against the scene's materials and textures.
TextureBinding validate_texture_binding(const StratumTextureBinding& desc, const Scene& scene);

}  // namespace stratum
