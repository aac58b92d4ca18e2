// Applies a scene's texture bindings to the closures of a shading point, after the integrator
// has copied the material's closures (RenderScene::material) for the hit.
//
// | parameter     | value written (t = texel looked up at the hit's UV)                    |
// |---------------|-------------------------------------------------------------------------|
// | BaseColor     | max(offset + scale t.rgb, 0)  (channel k: t[k] on all three)            |
// | Roughness,    | clamp(offset + scale y, 0, 1)   y = t[channel], or for channel -1 the   |
// | Metallic      |   luminance 0.2126729 r + 0.7151522 g + 0.0721750 b: Cycles converts a  |
// |               |   colour to a float socket with linear_rgb_to_gray (film rgb_to_y of    |
// |               |   the Rec.709 scene_linear space), svm/convert.h, 3.4 and 5.0           |
// | Specular      | max(offset + scale y, 0)                                               |
// | Weight        | closure weight *= clamp(offset + scale y, 0, 1) (Mix Shader's saturated |
// |               |   factor, svm_node_mix_closure)                                        |
// | Normal        | Cycles' Normal Map node, tangent space (svm/tex_coord.h): c = 2 t - 1,  |
// |               |   N' = normalize(c.x T + c.y B + c.z N), B = sign cross(N, T); strength |
// |               |   s = scale: if s != 1, N' = normalize(N + max(s, 0)(N' - N))           |
//
// Strength is Cycles 3.4's (a normalised lerp between N and the mapped normal). Cycles 4.x /
// 5.0 apply it in tangent space instead: c.xy *= s, c.z = mix(1, c.z, clamp(s, 0, 1)). With N
// orthogonal to T and a unit texel normal the two agree exactly for s in [0, 1]; they differ
// for s > 1 (4.x keeps c.z), s < 0 (4.x inverts the relief, 3.4 clamps to 0) and slightly for
// non-unit texels (8-bit quantisation).
//
// Tangent frame: a mesh given MikkTSpace corner tangents (Blender's, as Cycles takes them) uses
// Cycles' frame exactly (TangentFrame in scene/tangent_frame.h): T and N interpolated and not
// normalised, B = sign cross(N, T), N' = normalize(c.x T + c.y B + c.z N). Without them, T is
// the triangle's dpdu (constant per triangle) Gram-Schmidt orthogonalised against the
// interpolated shading normal and the sign is the triangle's UV orientation (+1 when
// (dpdu, dpdv, N) is right-handed, -1 for mirrored UVs): on smooth meshes dpdu jumps between
// triangles where MikkTSpace tangents vary smoothly, so curved normal-mapped surfaces show
// per-triangle facets (the textured sphere of scenes/features/materials.blend was +10% against
// Cycles that way); flat and UV-aligned surfaces agree exactly. A point without a tangent (no
// UVs: dpdu = 0) keeps its normal, as Cycles does without a tangent attribute. A normal binding on any
// closure of a material sets the point's one shading normal (Cycles perturbs only the closures wired to the
// node).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "scene/scene.h"
#include "scene/tangent_frame.h"
#include "texture/texture.h"
#include "texture/texture_binding.h"

namespace stratum {

// The bindings of a scene, grouped by material for the per-hit lookup; shares the scene's
// texture pixels.
class TextureBindings {
public:
    TextureBindings() = default;
    explicit TextureBindings(const Scene& scene);

    struct Bound {
        TextureBinding binding;
        const Texture* texture;
    };
    // The bindings of scene material `material_id` (empty if it has none).
    const std::vector<Bound>& of_material(uint32_t material_id) const {
        return material_id < per_material_.size() ? per_material_[material_id] : none_;
    }

private:
    std::vector<std::shared_ptr<const Texture>> textures_;
    std::vector<std::vector<Bound>> per_material_;
    std::vector<Bound> none_;
};

// Applies material `material_id`'s bindings at texture coordinate `uv` to its `count`
// closures (a copy of RenderScene::material(material_id).closures) and to the shading normal.
// shading_normal: unit, oriented as the triangle's winding (SurfaceHit::shading_normal, before
// any flip toward the viewer); frame: SurfaceHit::tangent_frame (see above).
void apply_texture_bindings(const TextureBindings& data, uint32_t material_id, Vec2 uv,
                            const TangentFrame& frame, WeightedClosure* closures, uint32_t count,
                            Vec3* shading_normal);

// The Normal Map node (tangent space) on its own: `color` the texel's RGB, `strength` the
// node's Strength, `normal` the unit shading normal. Returns `normal` unchanged when there is
// no usable tangent.
Vec3 apply_normal_map(Rgb color, float strength, Vec3 normal, const TangentFrame& frame);

}  // namespace stratum
