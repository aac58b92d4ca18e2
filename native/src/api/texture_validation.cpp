#include "api/texture_validation.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <new>
#include <optional>
#include <string>

#include "api/validation.h"
#include "texture/color_conversion.h"
#include "texture/image_reading.h"
#include "texture/texture_building.h"

namespace stratum {

namespace {

// Largest side accepted: beyond it width*height*4 floats would not fit the address space
// of any machine Blender runs on.
constexpr uint32_t kMaxTextureSide = 65536;

const char* const kParamNames[] = {"BASE_COLOR", "ROUGHNESS", "METALLIC",     "NORMAL",
                                   "EMISSION",   "WEIGHT",    "TRANSMISSION", "SPECULAR"};

void validate_source(const StratumTextureDesc& d) {
    const int sources = (d.path != nullptr) + (d.file_data != nullptr) + (d.pixels != nullptr);
    require(sources == 1,
            "texture needs exactly one of path, file_data and pixels (got " + std::to_string(sources) + ")");
    if (d.path) require(d.path[0] != '\0', "texture path is empty");
    if (d.file_data) {
        require(d.file_size > 0, "texture file_data has file_size 0");
        require(d.file_name && d.file_name[0] != '\0',
                "texture file_data needs file_name (its extension chooses the image reader)");
        require(!std::filesystem::path(d.file_name).extension().empty(),
                std::string("texture file_name '") + d.file_name +
                    "' has no extension to choose the image reader");
    } else {
        require(d.file_size == 0,
                "texture file_size is " + std::to_string(d.file_size) + " without file_data");
    }
    if (d.pixels) {
        require(d.width > 0 && d.width <= kMaxTextureSide,
                "texture width " + std::to_string(d.width) + " is outside [1, 65536]");
        require(d.height > 0 && d.height <= kMaxTextureSide,
                "texture height " + std::to_string(d.height) + " is outside [1, 65536]");
        require(d.channels >= 1 && d.channels <= 4,
                "texture channels " + std::to_string(d.channels) + " is outside [1, 4]");
        // Non-finite values are allowed: they become transparent black texels, as from files.
        check_decode_memory("pixels", d.width, d.height, d.channels, sizeof(float));
    } else {
        require(
            d.width == 0 && d.height == 0 && d.channels == 0,
            "texture width/height/channels describe `pixels` and must be 0 with a path or file_data (got " +
                std::to_string(d.width) + ", " + std::to_string(d.height) + ", " +
                std::to_string(d.channels) + ")");
    }
}

}  // namespace

std::shared_ptr<const Texture> load_texture(const StratumTextureDesc& d) {
    validate_source(d);
    require(d.color_space && d.color_space[0] != '\0', "texture color_space is NULL or empty");
    require(d.interpolation == STRATUM_TEXTURE_CLOSEST || d.interpolation == STRATUM_TEXTURE_LINEAR,
            "texture interpolation " + std::to_string(d.interpolation) + " is not 0 (closest) or 1 (linear)");
    require(
        d.extension >= STRATUM_TEXTURE_REPEAT && d.extension <= STRATUM_TEXTURE_MIRROR,
        "texture extension " + std::to_string(d.extension) + " is not 0..3 (repeat, extend, clip, mirror)");

    // The colour space first: a wrong name is refused before a large image is read.
    std::optional<SceneLinearConversion> conversion;
    try {
        conversion.emplace(conversion_to_scene_linear(d.ocio_config, d.color_space));
    } catch (const std::invalid_argument& e) {
        throw ValidationError(std::string("texture color_space: ") + e.what());
    }
    const StoredImage image = d.path        ? read_image_file(d.path)
                              : d.file_data ? read_image_memory(d.file_data, d.file_size, d.file_name)
                                            : image_from_pixels(d.pixels, d.width, d.height, d.channels);
    auto texture = std::make_shared<Texture>();
    try {
        SceneLinearTexels texels = scene_linear_texels(image, *conversion);
        texture->rgba = std::move(texels.rgba);
        texture->replaced_texels = texels.replaced_texels;
        texture->srgb_encoded = texels.srgb_encoded;
    } catch (const std::bad_alloc&) {
        throw ImageReadError("not enough memory for the " + std::to_string(image.width) + " x " +
                             std::to_string(image.height) + " texture of image '" +
                             (d.path        ? d.path
                              : d.file_data ? d.file_name
                                            : "pixels") +
                             "'");
    }
    texture->width = image.width;
    texture->height = image.height;
    texture->interpolation = static_cast<TextureInterpolation>(d.interpolation);
    texture->extension = static_cast<TextureExtension>(d.extension);
    return texture;
}

TextureBinding validate_texture_binding(const StratumTextureBinding& d, const Scene& scene) {
    require(d.material_id < scene.materials.size(), "binding material_id " + std::to_string(d.material_id) +
                                                        " is not a material (the scene has " +
                                                        std::to_string(scene.materials.size()) + ")");
    const size_t closures = scene.materials[d.material_id].closures.size();
    require(d.closure_index < closures, "binding closure_index " + std::to_string(d.closure_index) +
                                            " is not a closure of material " + std::to_string(d.material_id) +
                                            " (it has " + std::to_string(closures) + ")");
    require(d.param >= STRATUM_PARAM_BASE_COLOR && d.param <= STRATUM_PARAM_SPECULAR,
            "binding param " + std::to_string(d.param) + " is not a StratumMaterialParam (0..7)");
    const std::string param = kParamNames[d.param];
    require(
        d.param != STRATUM_PARAM_EMISSION,
        "binding param EMISSION: textured emission is not supported (emissive triangles are light-sampled "
        "with one constant emission each, so a texture would disagree between hits and light samples)");
    require(
        d.param != STRATUM_PARAM_TRANSMISSION,
        "binding param TRANSMISSION: the renderer's materials have no transmission parameter to texture yet");
    require(d.texture_id < scene.textures.size(), "binding texture_id " + std::to_string(d.texture_id) +
                                                      " is not a texture (the scene has " +
                                                      std::to_string(scene.textures.size()) + ")");
    require(d.channel >= -1 && d.channel <= 3,
            "binding channel " + std::to_string(d.channel) + " is not -1 (RGB) or 0..3 (R, G, B, A)");
    require(d.param != STRATUM_PARAM_NORMAL || d.channel == -1,
            "binding param NORMAL needs channel -1 (the RGB normal), got " + std::to_string(d.channel));
    require(std::isfinite(d.scale), "binding scale " + std::to_string(d.scale) + " is not finite");
    require(std::isfinite(d.offset), "binding offset " + std::to_string(d.offset) + " is not finite");
    require(d.emission_strength == 0.0f, "binding emission_strength " + std::to_string(d.emission_strength) +
                                             " must be 0 (" + param + " is not EMISSION)");
    TextureBinding b;
    b.material_id = d.material_id;
    b.closure_index = d.closure_index;
    b.param = static_cast<MaterialParam>(d.param);
    b.texture_id = d.texture_id;
    b.channel = d.channel;
    b.scale = d.scale;
    b.offset = d.offset;
    return b;
}

}  // namespace stratum
