// The scene in render-ready form: one object-space BVH per placed mesh and one Embree instance
// per placement (accel/embree_scene.h), emissive triangles and light objects in one LightSet,
// and the shading data a hit needs, computed from the prototype mesh and the instance transform
// (at the ray's time for a moving instance).
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "accel/embree_scene.h"
#include "bsdf/closure_set.h"
#include "lights/light_set.h"
#include "render_scene/material_programs.h"
#include "render_scene/material_texturing.h"
#include "scene/live_scene.h"
#include "scene/scene.h"
#include "scene/tangent_frame.h"

namespace stratum {

// Everything the integrator needs to know about a ray hit.
struct SurfaceHit {
    Vec3 position;
    Vec3 geometric_normal;  // unit, oriented as the triangle's winding
    Vec3 shading_normal;    // unit, interpolated corner normal (or the geometric normal)
    const Material* material;
    uint32_t emissive_light;            // index in the LightSet, or kNoLight
    Vec2 uv{0.0f, 0.0f};                // interpolated corner_uvs (0,0 if the mesh has none)
    TangentFrame tangent_frame;         // for normal maps: MikkTSpace corners, else the triangle's dpdu
    uint32_t material_id = 0;           // scene material id
    uint32_t visibility = kVisibleAll;  // the instance's StratumVisibility bits
    bool holdout = false;               // the instance is a holdout
    uint32_t lightgroup = 0;            // the light group of the instance's emission (0 none)
    uint32_t object_pass_index = 0;     // the instance's and the material's pass indices
    uint32_t material_pass_index = 0;   // (the IndexOB and IndexMA passes)
    float t = 0.0f;                     // distance along the ray (for LightSet::lamp_radiance's t_max)
    Vec3 object_position{};             // the point in the object's space (interpolated vertices)
    Vec3 dpdv{};                        // with tangent_frame.dpdu: the UV map's derivatives (0 without UVs)
    Vec2 barycentric{0.0f, 0.0f};       // (b1, b2): weights of the triangle's second and third vertex
    uint32_t placement = 0;             // the traced placement (RenderScene::program_inputs)
    uint32_t triangle = 0;              // the triangle of the placement's mesh
    std::array<Vec3, 3> vertices{};     // the triangle's corners in world space (at the ray's time)
    LightLinks links;                   // the instance's light and shadow linking sets
};

inline constexpr uint32_t kNoLight = 0xffffffffu;

// What a ray is for: the shutter time it samples (motion blur) and the StratumVisibility bit of
// its kind (CAMERA, DIFFUSE, GLOSSY, TRANSMISSION or SHADOW), matched against each instance's
// visibility: the ray sees an instance iff (visibility & instance visibility) != 0.
struct RayQuery {
    float time = 0.5f;
    uint32_t visibility = kVisibleAll;
};

enum class BvhLayout : uint8_t { Static, Dynamic };

// An axis-aligned box; empty until a point is added.
struct Bounds {
    Vec3 lo{kInfinity, kInfinity, kInfinity}, hi{-kInfinity, -kInfinity, -kInfinity};
    void add(Vec3 p) {
        lo = Vec3(std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z));
        hi = Vec3(std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z));
    }
    bool empty() const { return !(lo.x <= hi.x); }
};

// Emitted radiance of a material: sum_i weight_i ⊙ emission_i over its closures.
Rgb material_emission(const SceneMaterial& material);

class RenderScene {
public:
    // Throws std::runtime_error with a readable message (caught at the C ABI), BuildCancelled
    // when *cancel (may be null) becomes true during the build.
    // `bvh`: how the BVH is laid out (static: single placements flattened, fastest to trace;
    // dynamic: every mesh instanced, so that moving any object is cheap to update).
    explicit RenderScene(const Scene& scene, const std::atomic<bool>* cancel = nullptr,
                         BvhLayout bvh = BvhLayout::Static);
    BvhLayout bvh_layout() const { return bvh_; }

    // Applies edits of the scene it was built from (`scene` is that scene, edited; its meshes
    // are where they were): re-places edited instances in the BVH, takes the new materials,
    // lamps and world, and lists the lights anew, giving what a fresh build of `scene` gives.
    // False when the edits need a fresh build (a changed instance list, mesh or motion, or an
    // instance becoming traceable or not); then this scene must not be used any more.
    bool update(const Scene& scene, const SceneChanges& changes, const std::atomic<bool>* cancel = nullptr);

    struct BuildCancelled : std::runtime_error {
        BuildCancelled() : std::runtime_error("the scene build was cancelled") {}
    };
    // What the build left out and why, one sentence each (placements that cannot be traced).
    const std::vector<std::string>& notices() const { return notices_; }
    // Rays refused before Embree could reject them (EmbreeScene::refused_rays).
    uint64_t refused_rays() const { return embree_.refused_rays(); }

    bool intersect(Vec3 origin, Vec3 direction, float t_min, float t_max, SurfaceHit* hit,
                   const RayQuery& query = {}) const;
    // The closest hit as the BVH reports it (placement, triangle, barycentrics, t), without
    // shading it: for methods that only need which surface element a ray meets (radiosity).
    bool intersect_triangle(Vec3 origin, Vec3 direction, float t_min, float t_max, RayHit* hit,
                            const RayQuery& query = {}) const {
        return embree_.intersect(origin, direction, t_min, t_max, query.time, query.visibility, hit);
    }
    // The traced placements (RayHit::instance numbers them) and their triangles in world space
    // (a moving placement at shutter open), for methods that work on the surfaces themselves.
    struct PlacedTriangle {
        Vec3 p0, p1, p2;
        uint32_t material_id;
    };
    uint32_t placement_count() const { return static_cast<uint32_t>(instances_.size()); }
    uint32_t placement_triangle_count(uint32_t placement) const {
        return static_cast<uint32_t>(instances_[placement].mesh->triangles.size());
    }
    PlacedTriangle placed_triangle(uint32_t placement, uint32_t triangle) const {
        const InstanceData& g = instances_[placement];
        const auto& tri = g.mesh->triangles[triangle];
        const Transform& m = g.object_to_world;
        return {m.point(g.mesh->positions[tri[0]]), m.point(g.mesh->positions[tri[1]]),
                m.point(g.mesh->positions[tri[2]]), g.mesh->material_ids[triangle]};
    }
    bool occluded(Vec3 origin, Vec3 direction, float t_min, float t_max, const RayQuery& query = {}) const {
        return embree_.occluded(origin, direction, t_min, t_max, query.time, query.visibility);
    }
    const LightSet& lights() const { return lights_; }
    // Light linking: the lights that light surfaces of receiver set `receiver_set`
    // (LightSet::lighting; all lights without light linking), which NEE at such a surface
    // chooses among and whose probabilities the MIS weights of the emission a ray scattered
    // there finds are; and the index there of light `index` of lights() (LightSet::kNoLightIndex
    // when it does not light the set).
    const LightSet& lights_for(uint8_t receiver_set) const {
        return receiver_lights_[receiver_set] ? *receiver_lights_[receiver_set] : lights_;
    }
    uint32_t light_index_for(uint8_t receiver_set, uint32_t index) const {
        return receiver_lights_[receiver_set] ? receiver_index_[receiver_set][index] : index;
    }
    // Whether any material has a Transparent closure: only then can a shadow ray pass a surface,
    // so without one a shadow ray needs Embree's any-hit query alone, not the closest surface.
    bool has_transparent_closures() const { return has_transparent_closures_; }
    // The closures of scene material `id` (SurfaceHit::material_id), before texturing.
    const SceneMaterial& material(uint32_t id) const { return materials_[id]; }
    // The same as a finalized closure set, built once per material: a shading point copies it
    // rather than building and finalizing its own.
    const ClosureSet& closure_set(uint32_t id) const { return closure_sets_[id]; }
    // Image textures bound to material parameters (applied per shading point).
    const TextureBindings& textures() const { return textures_; }
    // Shader-node programs bound to material parameters (applied per shading point, after the
    // textures), and what their inputs are made of at a hit.
    const MaterialPrograms& programs() const { return programs_; }
    ProgramInputs program_inputs(const SurfaceHit& hit, Vec3 wo, bool backfacing, RayReach reach) const;
    // True if some traced instance is a shadow catcher that is not a holdout (Cycles'
    // has_shadow_catcher: only then do camera paths split, integrators/shadow_catcher.h).
    bool has_shadow_catcher() const { return has_shadow_catcher_; }
    // The light group of the world (background and environment; 0 none).
    uint32_t world_lightgroup() const { return world_lightgroup_; }
    // True if some instance moves over the shutter (the renderer then samples ray times).
    bool has_motion() const { return has_motion_; }
    // A sphere bounding the scene's geometry (radius >= 1), over which the light tracer emits
    // the sun's and the environment's parallel beams.
    Vec3 bounds_center() const { return bounds_center_; }
    float bounds_radius() const { return bounds_radius_; }
    // Radiance of a ray that leaves the scene in direction `dir`: the environment image if
    // there is one, else the constant background.
    Rgb background(Vec3 dir) const {
        const EnvironmentLight* env = lights_.environment();
        return env ? env->radiance(dir) : background_;
    }
    // The same for a ray of a path in state `path` (LightPathState::background): a world program
    // that reads the Light Path node runs for it (lights/world_program.h).
    Rgb background(Vec3 dir, const LightPathState& path) const {
        const WorldProgram* program = lights_.world_program();
        return program ? program->radiance(dir, path) : background(dir);
    }

private:
    struct InstanceData {
        const Mesh* mesh;
        uint32_t mesh_id;
        Transform object_to_world;  // static instances; moving ones ask Embree at the ray's time
        bool motion;
        uint32_t visibility;
        bool holdout;
        uint32_t pass_index;
        std::vector<uint32_t> emissive_light;  // per triangle, kNoLight if not emissive; empty if none
        float random;                          // Object Info: Random, colour and alpha
        Rgb color;
        float alpha;  // per triangle, kNoLight if not emissive; empty if none
        LightLinks links;
        uint32_t lightgroup;
    };
    static bool is_moving(const Instance& inst);
    // Whether Embree can trace the placement under the current ray-origin limit.
    bool traceable_placement(const Instance& inst) const;
    // The largest |coordinate| a ray origin can have in `scene` (scene/scene_limits.h).
    float origin_limit(const Scene& scene) const;
    // Sets has_shadow_catcher_ from the traced instances.
    void find_shadow_catchers();
    // Lists the emissive triangles, lamps and environment, and the scene's bounding sphere.
    void build_lights(const Scene& scene, const std::atomic<bool>* cancel);

    // Takes the scene's materials, builds each one's finalized closure set and notes whether any
    // has a Transparent closure.
    void set_materials(const Scene& scene);
    // The camera's inverse transform, for the programs' camera coordinates.
    void set_camera(const Scene& scene);

    std::vector<SceneMaterial> materials_;
    std::vector<ClosureSet> closure_sets_;  // per material
    bool has_transparent_closures_ = false;
    TextureBindings textures_;
    MaterialPrograms programs_;
    std::optional<Transform> world_to_camera_;   // camera coordinates of the programs' inputs
    std::vector<InstanceData> instances_;        // per traced placement
    std::vector<InstancePlacement> placements_;  // per traced placement, as given to Embree
    std::vector<uint32_t> placement_of_;         // per scene instance: its placement, or kNoLight
    std::vector<uint32_t> instance_mesh_;        // per scene instance: its mesh as built
    std::vector<Bounds> mesh_bounds_;            // object-space bounds of each placed mesh
    float limit_ = 0.0f;                         // the ray-origin limit the BVH was built for
    EmbreeScene embree_;
    LightSet lights_;
    // Per receiver set some instance has, when some light links (lights_for): its lights and the
    // index map from lights_.
    std::array<std::unique_ptr<const LightSet>, kMaxLinkSet + 1> receiver_lights_;
    std::array<std::vector<uint32_t>, kMaxLinkSet + 1> receiver_index_;
    Rgb background_;
    BvhLayout bvh_ = BvhLayout::Static;
    bool has_shadow_catcher_ = false;
    uint32_t world_lightgroup_ = 0;
    bool has_motion_ = false;
    Vec3 bounds_center_{0.0f, 0.0f, 0.0f};
    float bounds_radius_ = 1.0f;
    std::vector<std::string> notices_;
};

}  // namespace stratum
