#include "scene/render_scene.h"

#include <stdexcept>

namespace stratum {

RenderScene::RenderScene(const Scene& scene) : materials_(scene.materials), background_(scene.background) {
    instances_.reserve(scene.instances.size());
    Vec3 lo(kInfinity, kInfinity, kInfinity), hi(-kInfinity, -kInfinity, -kInfinity);
    for (const Instance& inst : scene.instances) {
        const Mesh& mesh = scene.meshes.at(inst.mesh_id);
        InstanceGeometry g{&mesh, {}, {}, {}};
        g.positions.reserve(mesh.positions.size());
        for (Vec3 p : mesh.positions) {
            const Vec3 w = inst.object_to_world.point(p);
            g.positions.push_back(w);
            lo = Vec3(std::min(lo.x, w.x), std::min(lo.y, w.y), std::min(lo.z, w.z));
            hi = Vec3(std::max(hi.x, w.x), std::max(hi.y, w.y), std::max(hi.z, w.z));
        }
        g.corner_normals.reserve(mesh.corner_normals.size());
        for (Vec3 n : mesh.corner_normals) {
            const Vec3 w = inst.object_to_world.normal(n);
            const float len = length(w);
            g.corner_normals.push_back(len > 0.0f ? w / len : Vec3(0, 0, 1));
        }
        instances_.push_back(std::move(g));
    }
    // Light objects for the choice among lights: each instance's emissive triangles form one,
    // then every lamp is one.
    uint32_t light_object = 0;
    for (InstanceGeometry& g : instances_) {
        const Mesh& mesh = *g.mesh;
        const uint32_t object = light_object++;
        for (size_t t = 0; t < mesh.triangles.size(); ++t) {
            const Material& m = materials_[mesh.material_ids[t]].closures.front().params;
            if (m.emission.is_black()) continue;
            if (g.emissive_light.empty()) g.emissive_light.assign(mesh.triangles.size(), kNoLight);
            const auto& tri = mesh.triangles[t];
            g.emissive_light[t] = lights_.add(
                EmissiveTriangle(g.positions[tri[0]], g.positions[tri[1]], g.positions[tri[2]], m.emission),
                object);
        }
    }
    for (const LightParams& l : scene.lights) {
        const Rgb power = l.color * l.strength;
        const uint32_t object = light_object++;
        switch (l.type) {
            case LightType::Point:
                lights_.add(PointLight(l.light_to_world.translation(), power, l.radius), object);
                break;
            case LightType::Sun:
                lights_.add(SunLight(normalize(l.light_to_world.vector(Vec3(0, 0, 1))), power, l.angle),
                            object);
                break;
            case LightType::AreaRectangle:
            case LightType::AreaEllipse:
                lights_.add(
                    AreaLight(l.light_to_world, l.size_x, l.size_y, l.type == LightType::AreaEllipse, power),
                    object);
                break;
            case LightType::Spot:
            case LightType::SpotV1:
                lights_.add(SpotLight(l.light_to_world, power, l.radius, l.spot_size, l.spot_blend,
                                      l.type == LightType::SpotV1),
                            object);
                break;
        }
    }
    if (scene.environment) {
        const Environment& e = *scene.environment;
        std::vector<float> rgb(e.rgb.size());
        for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = e.rgb[i] * e.strength;
        lights_.add(EnvironmentLight(std::move(rgb), e.width, e.height, e.rotation), light_object++);
    }
    // The sun's selection weight needs a scene size: the radius of the bounding box's sphere.
    lights_.finalize(lo.x <= hi.x ? std::max(1.0f, 0.5f * length(hi - lo)) : 1.0f);

    std::vector<TriangleGeometry> geometries;
    geometries.reserve(instances_.size());
    for (const InstanceGeometry& g : instances_) geometries.push_back({g.positions, g.mesh->triangles});
    const std::string error = embree_.build(geometries);
    if (!error.empty()) throw std::runtime_error(error);
}

bool RenderScene::intersect(Vec3 origin, Vec3 direction, float t_min, float t_max, SurfaceHit* hit,
                            const RayQuery& query) const {
    (void)query;
    RayHit h;
    if (!embree_.intersect(origin, direction, t_min, t_max, &h)) return false;
    const InstanceGeometry& g = instances_[h.geometry];
    const auto& tri = g.mesh->triangles[h.triangle];
    const Vec3 p0 = g.positions[tri[0]], p1 = g.positions[tri[1]], p2 = g.positions[tri[2]];
    const float b0 = 1.0f - h.b1 - h.b2;
    hit->position = p0 * b0 + p1 * h.b1 + p2 * h.b2;
    const Vec3 c = cross(p1 - p0, p2 - p0);
    const float len = length(c);
    hit->geometric_normal = len > 0.0f ? c / len : -direction;
    hit->shading_normal = hit->geometric_normal;
    if (!g.corner_normals.empty()) {
        const size_t k = 3 * static_cast<size_t>(h.triangle);
        const Vec3 n =
            g.corner_normals[k] * b0 + g.corner_normals[k + 1] * h.b1 + g.corner_normals[k + 2] * h.b2;
        const float nl = length(n);
        if (nl > 0.0f) hit->shading_normal = n / nl;
    }
    hit->material_id = g.mesh->material_ids[h.triangle];
    hit->material = &materials_[hit->material_id].closures.front().params;
    hit->emissive_light = g.emissive_light.empty() ? kNoLight : g.emissive_light[h.triangle];
    return true;
}

}  // namespace stratum
