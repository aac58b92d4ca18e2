// Image Texture inside a program (Blender's ShaderNodeTexImage feeding other nodes), as Cycles'
// svm/image.h (svm_node_tex_image, svm_image_texture; 3.4 and 5.0 agree), Flat projection.
//
// | node  | modes                                           | inputs       | outputs             |
// |-------|-------------------------------------------------|--------------|---------------------|
// | image | 0 texture id (checked against the scene's),     | 0 vector (3) | 0 color (3), 1 alpha |
// |       | 1 alpha (ImageAlpha: 0 straight, 1 associated,  |              |                     |
// |       | 2 associated then unassociated)                 |              |                     |
//
// The lookup is at (vector.x, vector.y) with the texture's own interpolation and extension
// (texture/texture.h). Cycles keeps colour images with their colour multiplied by alpha
// ("associated", done on the stored values: for an 8-bit sRGB image before the sRGB decoding) and
// interpolates them so; it divides by the interpolated alpha again (when alpha is neither 0 nor 1)
// only when the node's Alpha output is linked. The host picks the mode as Cycles does: 0 for
// Non-Color data and the Channel Packed and None alpha modes (stored as read), else 2 when Alpha
// is linked, else 1. Alpha is the interpolated alpha in every mode.
#include "shading/node_registry.h"
#include "texture/texture.h"

namespace stratum {

namespace {

enum ImageAlpha : int32_t { Straight, Associated, Unassociated, ImageAlphaCount };

std::string check_image(const ShaderNode& n, const ShaderProgram&) {
    // Mode 0 (the texture) is checked against the scene by the program's validation.
    return check_mode(n, 1, "alpha", ImageAlphaCount);
}

void evaluate_image(const ShaderNode& n, const ShaderEvalContext& context, ShaderRegisters& r) {
    const auto* textures = context.textures;
    const uint32_t id = static_cast<uint32_t>(n.modes[0]);
    if (textures == nullptr || id >= textures->size() || !(*textures)[id]) {
        // Cycles' colour for a missing image (TEX_IMAGE_MISSING_*): magenta, opaque.
        r.set(n.outputs[0], Rgb(1.0f, 0.0f, 1.0f));
        r[n.outputs[1]] = 1.0f;
        return;
    }
    const Texture& texture = *(*textures)[id];
    const Vec3 co = r.vec3(n.inputs[0]);
    Rgba v = texture_lookup_encoded(texture, Vec2{co.x, co.y}, n.modes[1] != Straight);
    if (n.modes[1] == Unassociated && v.a != 1.0f && v.a != 0.0f) {
        const float inverse = 1.0f / v.a;
        v = {v.r * inverse, v.g * inverse, v.b * inverse, v.a};
    }
    v = texture_decode(texture, v);
    r.set(n.outputs[0], Rgb(v.r, v.g, v.b));
    r[n.outputs[1]] = v.a;
}

}  // namespace

const NodeRegistration kImageNode{{.value = 18,
                                   .name = "image",
                                   .input_widths = {3},
                                   .output_widths = {3, 1},
                                   .check = check_image,
                                   .evaluate = evaluate_image,
                                   .texture_mode = 0}};

}  // namespace stratum
