#include "render_scene/material_texturing.h"

#include <algorithm>
#include <cmath>

namespace stratum {

namespace {

float scalar_of(const Rgba& t, int32_t channel) {
    switch (channel) {
        case 0:
            return t.r;
        case 1:
            return t.g;
        case 2:
            return t.b;
        case 3:
            return t.a;
        default:
            return kLuminanceR * t.r + kLuminanceG * t.g + kLuminanceB * t.b;
    }
}

Rgb color_of(const Rgba& t, int32_t channel) {
    if (channel < 0) return {t.r, t.g, t.b};
    return Rgb(scalar_of(t, channel));
}

Rgb max0(Rgb c) { return {std::max(c.r, 0.0f), std::max(c.g, 0.0f), std::max(c.b, 0.0f)}; }

}  // namespace

TextureBindings::TextureBindings(const Scene& scene)
    : textures_(scene.textures), per_material_(scene.materials.size()) {
    for (const TextureBinding& b : scene.texture_bindings) {
        per_material_[b.material_id].push_back({b, textures_[b.texture_id].get()});
    }
}

Vec3 apply_normal_map(Rgb color, float strength, Vec3 normal, const TangentFrame& frame) {
    const Vec3 c(2.0f * color.r - 1.0f, 2.0f * color.g - 1.0f, 2.0f * color.b - 1.0f);
    Vec3 mapped;
    if (frame.mikktspace) {
        mapped = frame.tangent * c.x + frame.bitangent * c.y + frame.normal * c.z;
    } else {
        const Vec3 tangent_raw = frame.dpdu - normal * dot(normal, frame.dpdu);
        const float tangent_length = length(tangent_raw);
        if (!(tangent_length > 1e-12f)) return normal;
        const Vec3 tangent = tangent_raw / tangent_length;
        const Vec3 bitangent = cross(normal, tangent) * frame.bitangent_sign;
        mapped = tangent * c.x + bitangent * c.y + normal * c.z;
    }
    const float mapped_length = length(mapped);
    // Cycles keeps sd->N where the mapped normal is zero or not finite.
    if (!(mapped_length > 0.0f) || !std::isfinite(mapped_length)) return normal;
    Vec3 result = mapped / mapped_length;
    if (strength != 1.0f) {
        const Vec3 blended = normal + (result - normal) * std::max(strength, 0.0f);
        const float blended_length = length(blended);
        if (!(blended_length > 0.0f)) return normal;
        result = blended / blended_length;
    }
    return result;
}

void apply_texture_bindings(const TextureBindings& data, uint32_t material_id, Vec2 uv,
                            const TangentFrame& frame, WeightedClosure* closures, uint32_t count,
                            Vec3* shading_normal) {
    for (const TextureBindings::Bound& bound : data.of_material(material_id)) {
        const TextureBinding& b = bound.binding;
        if (b.closure_index >= count) continue;
        const Rgba t = texture_lookup(*bound.texture, uv);
        Material& m = closures[b.closure_index].params;
        const float scalar = b.offset + b.scale * scalar_of(t, b.channel);
        switch (b.param) {
            case MaterialParam::BaseColor:
                m.base_color = max0(Rgb(b.offset) + color_of(t, b.channel) * b.scale);
                break;
            case MaterialParam::Roughness:
                m.roughness = std::clamp(scalar, 0.0f, 1.0f);
                break;
            case MaterialParam::Metallic:
                m.metallic = std::clamp(scalar, 0.0f, 1.0f);
                break;
            case MaterialParam::Specular:
                m.specular = std::max(scalar, 0.0f);
                break;
            case MaterialParam::Weight:
                closures[b.closure_index].weight *= std::clamp(scalar, 0.0f, 1.0f);
                break;
            case MaterialParam::Normal:
                *shading_normal = apply_normal_map(color_of(t, b.channel), b.scale, *shading_normal, frame);
                break;
            case MaterialParam::Emission:
            case MaterialParam::Transmission:
                // Refused by stratum_scene_bind_texture (api/texture_validation.cpp): never stored.
                break;
        }
    }
}

}  // namespace stratum
