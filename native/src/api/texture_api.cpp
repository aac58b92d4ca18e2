// The texture entry points: stratum_scene_add_texture, stratum_scene_texture_info and
// stratum_scene_bind_texture.
#include <string>

#include "api/abi_guard.h"
#include "api/scene_handle.h"
#include "api/texture_validation.h"
#include "stratum/stratum.h"
#include "texture/image_reading.h"

extern "C" {

StratumStatus stratum_scene_add_texture(StratumScene* scene, const StratumTextureDesc* texture,
                                        uint32_t* out_id) {
    using namespace stratum::abi;
    return guarded("stratum_scene_add_texture", [&] {
        require(scene && texture, "scene or texture is NULL");
        std::shared_ptr<const stratum::Texture> loaded;
        try {
            loaded = stratum::load_texture(*texture);
        } catch (const stratum::ImageReadError& e) {
            return fail(STRATUM_ERROR_IO, std::string("stratum_scene_add_texture: ") + e.what());
        }
        const uint32_t id = scene->live->edit(stratum::LiveScene::Part::Structure, [&](stratum::Scene& s) {
            s.textures.push_back(std::move(loaded));
            return static_cast<uint32_t>(s.textures.size() - 1);
        });
        if (out_id) *out_id = id;
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_texture_info(const StratumScene* scene, uint32_t texture_id,
                                         StratumTextureInfo* out) {
    using namespace stratum::abi;
    return guarded("stratum_scene_texture_info", [&] {
        require(scene && out, "scene or out is NULL");
        *out = scene->live->read([&](const stratum::Scene& s) {
            require(texture_id < s.textures.size(), "texture_id " + std::to_string(texture_id) +
                                                        " is not a texture (the scene has " +
                                                        std::to_string(s.textures.size()) + ")");
            const stratum::Texture& t = *s.textures[texture_id];
            return StratumTextureInfo{t.width, t.height, t.replaced_texels};
        });
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_bind_texture(StratumScene* scene, const StratumTextureBinding* binding) {
    using namespace stratum::abi;
    return guarded("stratum_scene_bind_texture", [&] {
        require(scene && binding, "scene or binding is NULL");
        scene->live->edit(stratum::LiveScene::Part::Structure, [&](stratum::Scene& s) {
            const stratum::TextureBinding b = stratum::validate_texture_binding(*binding, s);
            // A later binding of the same parameter replaces the earlier one.
            for (stratum::TextureBinding& existing : s.texture_bindings) {
                if (existing.material_id == b.material_id && existing.closure_index == b.closure_index &&
                    existing.param == b.param) {
                    existing = b;
                    return;
                }
            }
            s.texture_bindings.push_back(b);
        });
        return STRATUM_OK;
    });
}

}  // extern "C"
