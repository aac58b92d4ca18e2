// The scene as the host describes it (object space meshes, instances, materials, lights,
// camera, world). Validated at the C ABI; turned into a render-ready form by RenderScene.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "core/math.h"
#include "scene/camera.h"
#include "scene/light_links.h"
#include "scene/material.h"
#include "scene/visibility.h"
#include "shading/program_binding.h"
#include "shading/shader_program.h"
#include "texture/texture.h"
#include "texture/texture_binding.h"

namespace stratum {

// Blender's rule for a degenerate texture space (BKE_mesh_texspace_calc): a half size of 0 reads
// 1, a tiny positive one 1e-5; others, negative ones included (a user may set them), are kept.
inline Vec3 texture_space_half_size(Vec3 half) {
    const auto fix = [](float v) { return v == 0.0f ? 1.0f : (v > 0.0f && v < 1e-5f ? 1e-5f : v); };
    return Vec3(fix(half.x), fix(half.y), fix(half.z));
}

struct Mesh {
    std::vector<Vec3> positions;
    std::vector<std::array<uint32_t, 3>> triangles;
    std::vector<Vec3> corner_normals;    // empty, or 3 per triangle
    std::vector<Vec3> vertex_normals;    // empty, or 1 per vertex (never both kinds)
    std::vector<Vec2> corner_uvs;        // empty, or 3 per triangle
    std::vector<Vec3> corner_tangents;   // empty, or 3 per triangle (MikkTSpace, object space)
    std::vector<float> corner_signs;     // bitangent signs, 3 per triangle with corner_tangents
    std::vector<uint32_t> material_ids;  // 1 per triangle
    // Bounding box of `positions` (object space), for the ABI's bound on placed extents.
    Vec3 bounds_lo{kHuge, kHuge, kHuge}, bounds_hi{-kHuge, -kHuge, -kHuge};
    // Blender's texture space (generated coordinates): centre and half size per axis; unset, the
    // bounding box (Blender's automatic texture space). Sizes pass texture_space_half_size().
    std::optional<std::array<Vec3, 2>> texture_space;
    // Attributes the node programs read (stratum_scene_set_mesh_attribute): per slot, RGBA per
    // triangle corner (empty: the mesh lacks it) and how its Fac is made.
    struct CornerAttribute {
        std::vector<float> rgba;
        int32_t kind = 0;
    };
    std::array<CornerAttribute, 4> attributes;
    static constexpr float kHuge = std::numeric_limits<float>::infinity();
};

// One closure of a material with its weight (Blender's Mix / Add Shader trees flattened).
struct WeightedClosure {
    Rgb weight{1.0f};
    Material params;
};

// A scene material: the sum of its weighted closures (one for a plain material).
struct SceneMaterial {
    std::vector<WeightedClosure> closures;
    // Blender's Material > Settings > Pass Index: what the IndexMA pass holds where the material
    // is seen (stratum_scene_set_material_pass_index).
    uint32_t pass_index = 0;
};

struct Instance {
    uint32_t mesh_id;
    Transform object_to_world;  // at shutter open, or always if static
    // Appended for issue 5 (StratumInstanceDesc): motion blur, ray visibility, holdout.
    Transform object_to_world_end;  // at shutter close; read when `motion`
    bool motion = false;
    uint32_t visibility = kVisibleAll;  // StratumVisibility bits
    bool holdout = false;
    // Appended for issue 14: Object > Relations > Pass Index, what the IndexOB pass holds.
    uint32_t pass_index = 0;
    // Appended for issue 18: Object Info's Random (Cycles: random_id / 0xFFFFFFFF), Color, Alpha.
    float random = 0.0f;
    Rgb color{1.0f};
    float alpha = 1.0f;
    // Light and shadow linking as receiver, occluder and emitter (stratum_scene_set_light_linking).
    LightLinks links;
    // Issue 34: the light group of its emission (0 none, k: group k; film/light_groups.h).
    uint32_t lightgroup = 0;
};

// A light as the host describes it (StratumLightDesc). size_x, size_y, spot_size, spot_blend and
// spread are read by some types only: a type's model checks those it reads
// (LightModel::check_own_params), the others keep these defaults.
struct LightParams {
    // The C ABI's StratumLightType value: lights/light_registry.cpp names the model of each, so
    // this layer lists none of them.
    int32_t type = -1;
    Rgb color{1.0f};
    float strength = 0.0f;  // W, or W/m^2 for the sun
    float radius = 0.0f;
    float angle = 0.0f;
    float size_x = 1.0f, size_y = 1.0f;
    float spot_size = kPi, spot_blend = 0.0f;
    Transform light_to_world;
    // StratumVisibility bits (0 at the ABI reads as these): a Blender lamp lights shadow catchers.
    uint32_t visibility = kVisibleAll | kVisibleShadowCatcher;
    uint32_t lightgroup = 0;  // 0 none, k: light group k (film/light_groups.h)
    float spread = kPi;       // area lights: Cycles' spread, (0, pi]
    // As an emitter (its memberships; a lamp is no receiver or occluder here): set apart by
    // stratum_scene_set_light_linking.
    LightLinks links;
};

// An equirectangular environment image (see lights/environment_light.h for the mapping).
struct Environment {
    std::vector<float> rgb;  // width*height*3 linear RGB, rows top to bottom (not × strength)
    uint32_t width = 0, height = 0;
    float strength = 1.0f;
    std::array<float, 9> rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};  // world to environment, row-major
    // The world program the image was baked from, kept when it reads the Light Path node: it then
    // runs for each ray that leaves the scene (lights/world_program.h); null otherwise.
    std::shared_ptr<const ShaderProgram> program;
    uint32_t program_color = 0;  // the register of its colour
    std::vector<std::shared_ptr<const Texture>> program_textures;
};

struct Scene {
    std::vector<SceneMaterial> materials;
    std::vector<Mesh> meshes;
    std::vector<Instance> instances;
    std::vector<LightParams> lights;
    std::optional<CameraParams> camera;
    Rgb background{0.0f};
    std::optional<Environment> environment;  // replaces the background when present
    uint32_t world_lightgroup = 0;           // 0 none, k: light group k (film/light_groups.h)
    // Image textures (shared: copies of a Scene share the pixels) and the material parameters
    // they drive; at most one binding per (material, closure, parameter).
    std::vector<std::shared_ptr<const Texture>> textures;
    std::vector<TextureBinding> texture_bindings;
    // Shader node programs (shading/shader_program.h) and the closure parameters they drive; at
    // most one binding per (material, closure, parameter).
    std::vector<std::shared_ptr<const ShaderProgram>> programs;
    std::vector<ProgramBinding> program_bindings;
    // The lamps (of `lights`) whose emission a program scales, at most one program each.
    std::vector<LightProgram> light_programs;
};

}  // namespace stratum
