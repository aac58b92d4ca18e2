// All lights of a scene and the discrete distributions that next-event estimation (and the
// light tracer's emission) choose them by, one per LightSelection:
// * power (textbook 5.14): p(j) = Φ_j / ΣΦ;
// * uniform: p(j) = 1/N over the N light entries (each emissive triangle is an entry);
// * mixed (the default): pure power-proportional choice starves a light whose power estimate is
//   small next to another's although it dominates somewhere (a dim lamp beside a sun whose
//   "power" is its flux through the whole scene): its few samples carry huge weights and the
//   image shows dark pixels where it was never chosen. So the default is a defensive mixture:
//   half by power, half uniform over light objects (a Blender lamp, or all emissive triangles
//   of one object, chosen within the object by power):
//       p(j) = ½ Φ_j / ΣΦ + ½ (1/G) Φ_j / Φ_g(j),   G objects, Φ_g the power of j's object.
// Any p > 0 wherever a light contributes keeps NEE unbiased; a zero total power makes the
// power choice uniform.
#pragma once

#include <array>
#include <concepts>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "lights/emissive_triangle.h"
#include "lights/environment_light.h"
#include "lights/light.h"
#include "lights/light_selection.h"

namespace stratum {

class LightSet {
public:
    // `object` groups lights that belong to one scene object (the triangles of one emissive
    // mesh); every Blender lamp is an object of its own. `visibility` (StratumVisibility bits)
    // is copied into every LightSample of the light. Returns the index of the added light.
    uint32_t add(std::unique_ptr<const Light> light, uint32_t object, uint32_t visibility = kVisibleAll);
    template <std::derived_from<Light> L>
    uint32_t add(L light, uint32_t object, uint32_t visibility = kVisibleAll) {
        static_assert(!std::same_as<L, EnvironmentLight>, "the environment goes through add_environment");
        return add(std::make_unique<const L>(std::move(light)), object, visibility);
    }
    // The environment (at most one): a light like the others, which background() also looks up.
    uint32_t add_environment(EnvironmentLight environment, uint32_t object);
    // scene_radius: radius of a sphere bounding the scene, to give the sun and the environment a
    // power.
    void finalize(float scene_radius);

    bool empty() const { return lights_.empty(); }
    size_t size() const { return lights_.size(); }
    const Light& light(uint32_t index) const { return *lights_[index]; }
    uint32_t visibility(uint32_t index) const { return visibility_[index]; }
    // Power Φ_j of light `index` (W; the sun's and the environment's through the scene's
    // cross-section), as the selection distributions use it.
    double power(uint32_t index) const { return power_[index]; }
    // The probability with which `selection` chooses light `index`.
    float probability(uint32_t index, LightSelection selection = LightSelection::Mixed) const {
        return probability_[static_cast<size_t>(selection)][index];
    }
    // The light `selection` chooses for u in [0,1); size() when there are no lights.
    uint32_t choose(float u, LightSelection selection = LightSelection::Mixed) const;
    // Chooses a light with u_choice and samples it with u for the shading point p of normal n
    // (unit; 0 when it has none); out->pdf includes the choice. `triangle` is how a point on a
    // chosen emissive triangle is taken (n shapes it: lights/emissive_triangle.h).
    bool sample(Vec3 p, Vec3 n, float u_choice, Vec2 u, LightSample* out,
                LightSelection selection = LightSelection::Mixed,
                TriangleSampling triangle = TriangleSampling::SolidAngle) const;
    // Light tracing: chooses a light with u_choice by `selection` and emits a particle from it
    // (the lights' sample_emission); out->weight is divided by the choice probability, so it
    // estimates the scene's total emitted flux. The sun and the environment shine over the
    // scene's bounding sphere (center, radius). False when the chosen light emits nothing.
    bool sample_emission(float u_choice, Vec2 u_position, Vec2 u_direction, LightSelection selection,
                         Vec3 center, float radius, EmissionSample* out) const;
    // Pdf (choice × solid angle) with which sample() at (p, n) reaches `hit` on emissive
    // triangle `index` (a SurfaceHit's emissive_light: always an EmissiveTriangle).
    float emissive_triangle_pdf(uint32_t index, Vec3 p, Vec3 n, Vec3 hit,
                                LightSelection selection = LightSelection::Mixed,
                                TriangleSampling triangle = TriangleSampling::SolidAngle) const;
    // Radiance of the nearest lamp surface (an area lamp, or the disk of a point/spot lamp with
    // a radius, facing the ray's origin) whose visibility has bit `visibility` and whose
    // emitting face the ray (dir unit) meets before t_max; black if none. Lamps are not in the
    // BVH: this is how camera rays (Cycles' Object > Visibility > Camera on a light) and
    // BSDF-scattered rays find them. *pdf (if not null) = the pdf (choice × solid angle) with
    // which sample() at `origin` picks that direction, for MIS.
    // *t (if not null) = the distance to the lamp.
    Rgb lamp_radiance(Vec3 origin, Vec3 dir, float t_max, uint32_t visibility, float* pdf = nullptr,
                      float* t = nullptr, LightSelection selection = LightSelection::Mixed) const;
    // The environment (at most one), or null; its pdf (choice × solid angle) for direction wi.
    const EnvironmentLight* environment() const { return environment_; }
    float environment_pdf(Vec3 wi, LightSelection selection = LightSelection::Mixed) const;
    // Whether some light can be reached only by light sampling: a point or spot lamp of radius
    // 0 or a sun of angle 0 (delta lights no scattered ray finds).
    bool has_delta_lights() const { return delta_lights_ > 0; }
    uint32_t delta_light_count() const { return delta_lights_; }

private:
    std::vector<std::unique_ptr<const Light>> lights_;
    std::vector<uint32_t> object_;          // object of each light
    std::vector<uint32_t> visibility_;      // StratumVisibility bits of each light
    std::vector<uint32_t> hittable_lamps_;  // lamps with a surface rays meet (lamp_radiance)
    std::vector<double> power_;             // Φ_j, set by finalize()
    // Per LightSelection: cdf[i] = P(choice < i+1) (last = 1), and the choice probabilities.
    std::array<std::vector<float>, kLightSelectionModes> cdf_, probability_;
    uint32_t delta_lights_ = 0;
    const EnvironmentLight* environment_ = nullptr;  // owned by lights_
    uint32_t environment_index_ = 0;
};

}  // namespace stratum
