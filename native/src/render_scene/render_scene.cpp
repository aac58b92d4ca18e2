#include "render_scene/render_scene.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "bsdf/bsdf.h"
#include "lights/light_registry.h"
#include "scene/placement_conditioning.h"

namespace stratum {

namespace {

// World bounds of an object-space box under an affine map: the box of its 8 transformed corners.
void add_transformed(Bounds& world, const Bounds& object, const Transform& m) {
    if (object.empty()) return;
    for (int c = 0; c < 8; ++c) {
        world.add(m.point(Vec3(c & 1 ? object.hi.x : object.lo.x, c & 2 ? object.hi.y : object.lo.y,
                               c & 4 ? object.hi.z : object.lo.z)));
    }
}

float largest_coordinate(const Bounds& b) {
    if (b.empty()) return 0.0f;
    return std::max({std::abs(b.lo.x), std::abs(b.lo.y), std::abs(b.lo.z), std::abs(b.hi.x), std::abs(b.hi.y),
                     std::abs(b.hi.z)});
}

// The largest |coordinate| of anything a ray can start from besides geometry: lamps (with their
// size) and the camera (with its lens and, orthographic, its view plane).
float lamp_and_camera_extent(const Scene& scene) {
    float extent = 0.0f;
    for (const LightParams& l : scene.lights) {
        const Vec3 p = l.light_to_world.translation();
        const float reach = l.radius + std::max(l.size_x, l.size_y);
        extent = std::max({extent, std::abs(p.x) + reach, std::abs(p.y) + reach, std::abs(p.z) + reach});
    }
    if (scene.camera) {
        const CameraParams& c = *scene.camera;
        const Vec3 p = c.camera_to_world.translation();
        const float reach =
            c.aperture_radius + c.ortho_scale * (1.0f + std::abs(c.shift_x) + std::abs(c.shift_y));
        extent = std::max({extent, std::abs(p.x) + reach, std::abs(p.y) + reach, std::abs(p.z) + reach});
    }
    return extent;
}

// Ray origins lie on geometry, lamps or the lens, or, for the light tracer's sun and sky
// particles, on a disk of radius up to 20 R at distance R from the scene's bounding sphere
// centre (lights/sun_light.cpp: R (1 + sin)/cos with cos >= 0.1, R <= √3 × the extent): all
// within 40 times the scene's extent, so 64 times it (at least 64) bounds them with room for
// rounding. ABI bounds keep it below 64 × 1e12 (scene/scene_limits.h).
float ray_origin_limit(float extent) { return 64.0f * std::max(extent, 1.0f); }

Vec3 unit_or(Vec3 v, Vec3 fallback) {
    const float len = length(v);
    return len > 0.0f ? v / len : fallback;
}

}  // namespace

Rgb material_emission(const SceneMaterial& material) {
    Rgb sum(0.0f);
    for (const WeightedClosure& c : material.closures) sum += c.weight * c.params.emission;
    return sum;
}

void RenderScene::set_materials(const Scene& scene) {
    materials_ = scene.materials;
    closure_sets_.clear();
    closure_sets_.reserve(materials_.size());
    for (const SceneMaterial& m : materials_) closure_sets_.emplace_back(m);
    has_transparent_closures_ = std::any_of(materials_.begin(), materials_.end(), [](const SceneMaterial& m) {
        return std::any_of(m.closures.begin(), m.closures.end(), [](const WeightedClosure& c) {
            return closure_model(c.params.model).transparent;
        });
    });
}

RenderScene::RenderScene(const Scene& scene, const std::atomic<bool>* cancel, BvhLayout bvh)
    : textures_(scene), programs_(scene), background_(scene.background), bvh_(bvh) {
    set_materials(scene);
    set_camera(scene);
    // The scene's extent first: it decides which placements can be traced at all.
    mesh_bounds_.assign(scene.meshes.size(), Bounds{});
    std::vector<bool> bounded(scene.meshes.size(), false);
    for (const Instance& inst : scene.instances) {
        if (bounded[inst.mesh_id]) continue;
        for (Vec3 p : scene.meshes[inst.mesh_id].positions) mesh_bounds_.at(inst.mesh_id).add(p);
        bounded[inst.mesh_id] = true;
    }
    limit_ = origin_limit(scene);
    // One prototype BVH per mesh that is placed at least once.
    std::vector<uint32_t> prototype_of(scene.meshes.size(), kNoLight);
    std::vector<TriangleGeometry> prototypes;
    placements_.reserve(scene.instances.size());
    instances_.reserve(scene.instances.size());
    placement_of_.assign(scene.instances.size(), kNoLight);
    instance_mesh_.clear();
    for (const Instance& inst : scene.instances) instance_mesh_.push_back(inst.mesh_id);
    for (size_t index = 0; index < scene.instances.size(); ++index) {
        const Instance& inst = scene.instances[index];
        const Mesh& mesh = scene.meshes.at(inst.mesh_id);
        const bool moving = is_moving(inst);
        if (!traceable_placement(inst)) {
            notices_.push_back("instance " + std::to_string(index) + " (mesh " +
                               std::to_string(inst.mesh_id) +
                               ") has a degenerate transform (scale (nearly) 0 along some axis" +
                               (moving ? ", or through 0 over the shutter" : "") +
                               "): it cannot be ray traced and is skipped");
            continue;
        }
        if (prototype_of[inst.mesh_id] == kNoLight) {
            prototype_of[inst.mesh_id] = static_cast<uint32_t>(prototypes.size());
            prototypes.push_back({mesh.positions, mesh.triangles});
        }
        placement_of_[index] = static_cast<uint32_t>(placements_.size());
        placements_.push_back({prototype_of[inst.mesh_id], inst.object_to_world, inst.object_to_world_end,
                               moving, trace_visibility(inst.visibility)});
        if (moving) has_motion_ = true;
        instances_.push_back({&mesh,
                              inst.mesh_id,
                              inst.object_to_world,
                              moving,
                              inst.visibility,
                              inst.holdout,
                              inst.pass_index,
                              {},
                              inst.random,
                              inst.color,
                              inst.alpha,
                              inst.links,
                              inst.lightgroup});
    }
    find_shadow_catchers();
    build_lights(scene, cancel);
    const std::string error =
        embree_.build(prototypes, placements_, limit_, cancel, bvh == BvhLayout::Static);
    if (error == EmbreeScene::kBuildCancelled) throw BuildCancelled();
    if (!error.empty()) throw std::runtime_error(error);
}

void RenderScene::find_shadow_catchers() {
    has_shadow_catcher_ = std::ranges::any_of(instances_, [](const InstanceData& g) {
        return !g.holdout && (g.visibility & kVisibleShadowCatcher);
    });
}

bool RenderScene::is_moving(const Instance& inst) {
    // An exporter may flag every object as moving when motion blur is on: equal ends are static
    // (flattened if placed once, emissive triangles kept as lights).
    return inst.motion && inst.object_to_world.m != inst.object_to_world_end.m;
}

bool RenderScene::traceable_placement(const Instance& inst) const {
    const bool moving = is_moving(inst);
    const double inverse = inverse_norm_bound(inst.object_to_world, inst.object_to_world_end, moving);
    return traceable(inverse, translation_bound(inst.object_to_world, inst.object_to_world_end), limit_);
}

float RenderScene::origin_limit(const Scene& scene) const {
    Bounds all;
    for (const Instance& inst : scene.instances) {
        add_transformed(all, mesh_bounds_[inst.mesh_id], inst.object_to_world);
        if (inst.motion) add_transformed(all, mesh_bounds_[inst.mesh_id], inst.object_to_world_end);
    }
    // Motion can bulge a box past both ends' boxes by its rotation, up to √3 of its size.
    return ray_origin_limit(std::max(1.7321f * largest_coordinate(all), lamp_and_camera_extent(scene)));
}

void RenderScene::build_lights(const Scene& scene, const std::atomic<bool>* cancel) {
    lights_ = LightSet();
    world_lightgroup_ = scene.world_lightgroup;
    std::vector<Rgb> emission(materials_.size());
    for (size_t m = 0; m < materials_.size(); ++m) emission[m] = material_emission(materials_[m]);
    // Light objects for the choice among lights: each static instance's emissive triangles form
    // one, then every lamp is one. A moving emitter gets no light entries (a light sample drawn
    // at one shutter time could not be matched by the shadow ray's time): it is still found by
    // camera and BSDF rays, which then take the full MIS weight, so it is unbiased but noisier.
    uint32_t light_object = 0;
    for (InstanceData& g : instances_) {
        g.emissive_light.clear();
        if (g.motion) continue;
        const Mesh& mesh = *g.mesh;
        const uint32_t object = light_object++;
        for (size_t t = 0; t < mesh.triangles.size(); ++t) {
            // A mesh of millions of emissive triangles takes a while to list: cancel is
            // honoured here as in Embree's build.
            if (t % 65536 == 0 && cancel && cancel->load(std::memory_order_relaxed)) throw BuildCancelled();
            const Rgb& e = emission[mesh.material_ids[t]];
            if (e.is_black()) continue;
            if (g.emissive_light.empty()) g.emissive_light.assign(mesh.triangles.size(), kNoLight);
            const auto& tri = mesh.triangles[t];
            const Transform& m = g.object_to_world;
            g.emissive_light[t] = lights_.add(
                EmissiveTriangle(m.point(mesh.positions[tri[0]]), m.point(mesh.positions[tri[1]]),
                                 m.point(mesh.positions[tri[2]]), e),
                object, trace_visibility(kVisibleAll | (g.visibility & kVisibleShadowCatcher)), g.links);
            lights_.set_lightgroup(g.emissive_light[t], g.lightgroup);
        }
    }
    const uint32_t first_lamp = static_cast<uint32_t>(lights_.size());
    for (const LightParams& l : scene.lights)
        lights_.set_lightgroup(
            lights_.add(make_light(l), light_object++, trace_visibility(l.visibility), l.links),
            l.lightgroup);
    for (const LightProgram& p : scene.light_programs) {
        const uint32_t index = first_lamp + p.light_id;
        // A light that gives no bounds lies at infinity (lights/light.h).
        const bool at_infinity = !lights_.light(index).bounds();
        lights_.set_program(
            index, std::make_shared<const LampProgram>(scene.programs[p.program_id], p.register_index,
                                                       scene.textures, at_infinity));
    }
    if (scene.environment) {
        const Environment& e = *scene.environment;
        std::vector<float> rgb(e.rgb.size());
        // Saturating: a strength of 3e38 on a bright texel must not give an infinite sky.
        for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = saturating_product(Rgb(e.rgb[i]), e.strength).r;
        lights_.set_lightgroup(
            lights_.add_environment(EnvironmentLight(std::move(rgb), e.width, e.height, e.rotation),
                                    light_object++),
            scene.world_lightgroup);
        if (e.program)
            lights_.set_world_program(
                std::make_shared<const WorldProgram>(e.program, e.program_color, e.program_textures));
    }
    // The sun's selection weight needs a scene size: the radius of the bounding box's sphere.
    // Rotation is interpolated, so a moving box can bulge past both end boxes; the bound only
    // sizes the sun's selection weight, where that slack does not matter.
    Bounds world;
    for (const InstanceData& g : instances_) {
        add_transformed(world, mesh_bounds_[g.mesh_id], g.object_to_world);
        if (g.motion)
            add_transformed(world, mesh_bounds_[g.mesh_id], placements_[&g - instances_.data()].end);
    }
    bounds_center_ = Vec3(0.0f, 0.0f, 0.0f);
    bounds_radius_ = 1.0f;
    if (!world.empty()) {
        bounds_center_ = (world.lo + world.hi) * 0.5f;
        bounds_radius_ = std::max(1.0f, 0.5f * length(world.hi - world.lo));
    }
    lights_.finalize(bounds_radius_);
    for (uint32_t set = 0; set <= kMaxLinkSet; ++set) {
        receiver_lights_[set].reset();
        receiver_index_[set].clear();
    }
    if (lights_.has_light_linking()) {
        for (const InstanceData& g : instances_) {
            const uint8_t set = g.links.receiver_light_set;
            if (receiver_lights_[set]) continue;
            receiver_lights_[set] =
                std::make_unique<const LightSet>(lights_.lighting(set, &receiver_index_[set]));
        }
    }
}

bool RenderScene::update(const Scene& scene, const SceneChanges& changes, const std::atomic<bool>* cancel) {
    if (changes.rebuild || scene.instances.size() != placement_of_.size()) return false;
    // Every instance keeps its mesh, its motion and whether it can be traced under the new
    // extent (a moved object or lamp changes the ray-origin limit): else build anew, as a fresh
    // build would place them differently.
    for (const uint32_t i : changes.instances) {
        const Instance& inst = scene.instances[i];
        if (inst.mesh_id != instance_mesh_[i]) return false;
        const uint32_t placement = placement_of_[i];
        if (placement != kNoLight && placements_[placement].motion != is_moving(inst)) return false;
    }
    const float built_limit = limit_;
    limit_ = origin_limit(scene);
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        if (traceable_placement(scene.instances[i]) != (placement_of_[i] != kNoLight)) {
            limit_ = built_limit;
            return false;
        }
    }
    std::vector<uint32_t> moved;
    for (const uint32_t i : changes.instances) {
        const uint32_t placement = placement_of_[i];
        // Skipped as untraceable before the edit and after it (checked above): nothing to place.
        if (placement == kNoLight) continue;
        const Instance& inst = scene.instances[i];
        InstancePlacement& p = placements_[placement];
        p.start = inst.object_to_world;
        p.end = inst.object_to_world_end;
        p.mask = trace_visibility(inst.visibility);
        InstanceData& g = instances_[placement];
        g.object_to_world = inst.object_to_world;
        g.visibility = inst.visibility;
        g.holdout = inst.holdout;
        g.pass_index = inst.pass_index;
        g.random = inst.random;
        g.color = inst.color;
        g.alpha = inst.alpha;
        g.links = inst.links;
        g.lightgroup = inst.lightgroup;
        moved.push_back(placement);
    }
    if (changes.materials) {
        set_materials(scene);
        textures_ = TextureBindings(scene);
        programs_ = MaterialPrograms(scene);
    }
    find_shadow_catchers();
    if (changes.camera) set_camera(scene);
    if (changes.world) background_ = scene.background;
    // The light set depends on placed emitters, materials, lamps and world, not on the camera:
    // orbiting the view lists no light again.
    if (!moved.empty() || changes.materials || changes.lights || changes.world) build_lights(scene, cancel);
    const std::string error = embree_.update(placements_, moved, limit_);
    if (!error.empty()) throw std::runtime_error(error);
    return true;
}

namespace {

// Cycles' normal-map frame at barycentrics (b0, b1, b2) of triangle `tri` (corners k..k+2): the
// unnormalised interpolated tangent and sign, and the unnormalised interpolated smooth normal
// (or, flat, the object-space geometric normal turned as the world one), in object space, then
// through the normal transform (see TangentFrame).
void mikktspace_frame(const Mesh& mesh, size_t k, const std::array<uint32_t, 3>& tri, float b0, float b1,
                      float b2, const Transform& m, SurfaceHit* hit) {
    const Vec3 t =
        mesh.corner_tangents[k] * b0 + mesh.corner_tangents[k + 1] * b1 + mesh.corner_tangents[k + 2] * b2;
    const float sign =
        mesh.corner_signs[k] * b0 + mesh.corner_signs[k + 1] * b1 + mesh.corner_signs[k + 2] * b2;
    Vec3 n;
    if (!mesh.corner_normals.empty()) {
        n = mesh.corner_normals[k] * b0 + mesh.corner_normals[k + 1] * b1 + mesh.corner_normals[k + 2] * b2;
    } else if (!mesh.vertex_normals.empty()) {
        n = mesh.vertex_normals[tri[0]] * b0 + mesh.vertex_normals[tri[1]] * b1 +
            mesh.vertex_normals[tri[2]] * b2;
    } else {
        const Vec3 p0 = mesh.positions[tri[0]];
        n = unit_or(cross(mesh.positions[tri[1]] - p0, mesh.positions[tri[2]] - p0), Vec3(0.0f, 0.0f, 1.0f));
        if (dot(m.normal(n), hit->geometric_normal) < 0.0f) n = -n;
    }
    TangentFrame& f = hit->tangent_frame;
    f.mikktspace = true;
    f.tangent = m.normal(t);
    f.bitangent = m.normal(cross(n, t) * sign);
    f.normal = m.normal(n);
}

}  // namespace

bool RenderScene::intersect(Vec3 origin, Vec3 direction, float t_min, float t_max, SurfaceHit* hit,
                            const RayQuery& query) const {
    RayHit h;
    if (!embree_.intersect(origin, direction, t_min, t_max, query.time, query.visibility, &h)) return false;
    const InstanceData& g = instances_[h.instance];
    const Mesh& mesh = *g.mesh;
    const Transform m = g.motion ? embree_.motion_transform(h.instance, query.time) : g.object_to_world;
    const auto& tri = mesh.triangles[h.triangle];
    // World vertices first, then interpolation: the same arithmetic as a mesh flattened to world
    // space, so an identity instance shades exactly as the flattened mesh does.
    const Vec3 p0 = m.point(mesh.positions[tri[0]]), p1 = m.point(mesh.positions[tri[1]]),
               p2 = m.point(mesh.positions[tri[2]]);
    const float b0 = 1.0f - h.b1 - h.b2;
    hit->position = p0 * b0 + p1 * h.b1 + p2 * h.b2;
    const Vec3 e1 = p1 - p0, e2 = p2 - p0;
    hit->geometric_normal = unit_or(cross(e1, e2), -direction);
    hit->shading_normal = hit->geometric_normal;
    const size_t k = 3 * static_cast<size_t>(h.triangle);
    if (!mesh.corner_normals.empty()) {
        // Normals map by the inverse transpose (Transform::normal), each corner made unit first.
        const Vec3 fallback(0, 0, 1);
        const Vec3 n = unit_or(m.normal(mesh.corner_normals[k]), fallback) * b0 +
                       unit_or(m.normal(mesh.corner_normals[k + 1]), fallback) * h.b1 +
                       unit_or(m.normal(mesh.corner_normals[k + 2]), fallback) * h.b2;
        hit->shading_normal = unit_or(n, hit->geometric_normal);
    } else if (!mesh.vertex_normals.empty()) {
        // The same arithmetic with the triangle's vertices' normals as its corners'.
        const Vec3 fallback(0, 0, 1);
        const Vec3 n = unit_or(m.normal(mesh.vertex_normals[tri[0]]), fallback) * b0 +
                       unit_or(m.normal(mesh.vertex_normals[tri[1]]), fallback) * h.b1 +
                       unit_or(m.normal(mesh.vertex_normals[tri[2]]), fallback) * h.b2;
        hit->shading_normal = unit_or(n, hit->geometric_normal);
    }
    hit->uv = {0.0f, 0.0f};
    hit->tangent_frame = TangentFrame{};
    hit->dpdv = Vec3{};
    if (!mesh.corner_tangents.empty()) mikktspace_frame(mesh, k, tri, b0, h.b1, h.b2, m, hit);
    if (!mesh.corner_uvs.empty()) {
        const Vec2 t0 = mesh.corner_uvs[k], t1 = mesh.corner_uvs[k + 1], t2 = mesh.corner_uvs[k + 2];
        hit->uv = {t0.x * b0 + t1.x * h.b1 + t2.x * h.b2, t0.y * b0 + t1.y * h.b1 + t2.y * h.b2};
        // p − p0 = dpdu (u − u0) + dpdv (v − v0) on the triangle: solving the 2x2 system of the two
        // edges gives dpdu = (dv2 e1 − dv1 e2) / (du1 dv2 − du2 dv1) (pbrt 3.6.2). Degenerate UVs: 0.
        const float du1 = t1.x - t0.x, dv1 = t1.y - t0.y, du2 = t2.x - t0.x, dv2 = t2.y - t0.y;
        const float det = du1 * dv2 - du2 * dv1;
        if (det != 0.0f) {
            hit->tangent_frame.dpdu = (e1 * dv2 - e2 * dv1) / det;
            hit->dpdv = (e2 * du1 - e1 * du2) / det;
            hit->tangent_frame.bitangent_sign = det < 0.0f ? -1.0f : 1.0f;
        }
    }
    hit->material_id = mesh.material_ids[h.triangle];
    hit->material = &materials_[hit->material_id].closures.front().params;
    hit->emissive_light = g.emissive_light.empty() ? kNoLight : g.emissive_light[h.triangle];
    hit->visibility = g.visibility;
    hit->holdout = g.holdout;
    hit->lightgroup = g.lightgroup;
    hit->object_pass_index = g.pass_index;
    hit->links = g.links;
    hit->material_pass_index = materials_[hit->material_id].pass_index;
    hit->t = h.t;
    hit->object_position =
        mesh.positions[tri[0]] * b0 + mesh.positions[tri[1]] * h.b1 + mesh.positions[tri[2]] * h.b2;
    hit->barycentric = {h.b1, h.b2};
    hit->placement = h.instance;
    hit->triangle = h.triangle;
    hit->vertices = {p0, p1, p2};
    return true;
}

void RenderScene::set_camera(const Scene& scene) {
    world_to_camera_.reset();
    if (scene.camera) world_to_camera_ = scene.camera->camera_to_world.inverse();
}

ProgramInputs RenderScene::program_inputs(const SurfaceHit& hit, Vec3 wo, bool backfacing,
                                          RayReach reach) const {
    const InstanceData& g = instances_[hit.placement];
    const Mesh& mesh = *g.mesh;
    Vec3 loc, size;
    if (mesh.texture_space) {
        loc = (*mesh.texture_space)[0];
        size = (*mesh.texture_space)[1];
    } else {
        // Blender's automatic texture space: the bounding box, a flat axis read as size 1.
        const Bounds& b = mesh_bounds_[g.mesh_id];
        loc = (b.lo + b.hi) * 0.5f;
        size = texture_space_half_size((b.hi - b.lo) * 0.5f);
    }
    return {wo,
            backfacing,
            g.object_to_world.translation(),
            loc,
            size,
            g.random,
            g.color,
            g.alpha,
            world_to_camera_ ? &*world_to_camera_ : nullptr,
            &g.object_to_world,
            g.mesh,
            reach};
}

}  // namespace stratum
