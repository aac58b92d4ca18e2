// All lights of a scene and the discrete distribution that next-event estimation chooses them
// by. Pure power-proportional choice (textbook 5.14, p(j) = Φ_j / ΣΦ) starves a light whose
// power estimate is small next to another's although it dominates somewhere (a dim lamp beside
// a sun whose "power" is its flux through the whole scene): its few samples carry huge weights
// and the image shows dark pixels where it was never chosen. So the choice is a defensive
// mixture: half by power, half uniform over light objects (a Blender lamp, or all emissive
// triangles of one object, chosen within the object by power):
//     p(j) = ½ Φ_j / ΣΦ + ½ (1/G) Φ_j / Φ_g(j),   G objects, Φ_g the power of j's object.
// Any p > 0 wherever a light contributes keeps NEE unbiased.
#pragma once

#include <cstdint>
#include <variant>
#include <vector>

#include "lights/area_light.h"
#include "lights/emissive_triangle.h"
#include "lights/environment_light.h"
#include "lights/point_light.h"
#include "lights/spot_light.h"
#include "lights/sun_light.h"

namespace stratum {

class LightSet {
public:
    using Light =
        std::variant<PointLight, SunLight, AreaLight, EmissiveTriangle, SpotLight, EnvironmentLight>;

    // `object` groups lights that belong to one scene object (the triangles of one emissive
    // mesh); every Blender lamp is an object of its own. `visibility` (StratumVisibility bits)
    // is copied into every LightSample of the light. Returns the index of the added light.
    uint32_t add(Light light, uint32_t object, uint32_t visibility = 31);
    // scene_radius: radius of a sphere bounding the scene, to give the sun a power.
    void finalize(float scene_radius);

    bool empty() const { return lights_.empty(); }
    size_t size() const { return lights_.size(); }
    // Chooses a light with u_choice and samples it with u; out->pdf includes the choice.
    bool sample(Vec3 p, float u_choice, Vec2 u, LightSample* out) const;
    // Pdf (choice × solid angle) with which sample() reaches `hit` on emissive triangle `index`.
    float emissive_triangle_pdf(uint32_t index, Vec3 p, Vec3 hit) const;
    // Radiance of the nearest lamp surface (an area lamp, or the disk of a point/spot lamp with
    // a radius, facing the ray's origin) whose visibility has bit `visibility` and whose
    // emitting face the ray (dir unit) meets before t_max; black if none. Lamps are not in the
    // BVH: this is how camera rays (Cycles' Object > Visibility > Camera on a light) and
    // BSDF-scattered rays find them. *pdf (if not null) = the pdf (choice × solid angle) with
    // which sample() at `origin` picks that direction, for MIS.
    // *t (if not null) = the distance to the lamp.
    Rgb lamp_radiance(Vec3 origin, Vec3 dir, float t_max, uint32_t visibility, float* pdf = nullptr,
                      float* t = nullptr) const;
    // The environment (at most one), or null; its pdf (choice × solid angle) for direction wi.
    const EnvironmentLight* environment() const;
    float environment_pdf(Vec3 wi) const;

private:
    std::vector<Light> lights_;
    std::vector<uint32_t> object_;          // object of each light
    std::vector<uint32_t> visibility_;      // StratumVisibility bits of each light
    std::vector<uint32_t> hittable_lamps_;  // lamps with a surface rays meet (lamp_radiance)
    std::vector<float> cdf_;                // cdf_[i] = P(choice < i+1), last = 1
    std::vector<float> probability_;
    size_t environment_ = SIZE_MAX;  // index of the environment light, if any
};

}  // namespace stratum
