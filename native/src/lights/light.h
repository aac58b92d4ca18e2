// What every light model answers for itself, so that LightSet (and through it next-event
// estimation and the light tracer) never asks which model a light is.
//
// | question         | answer                                                                    |
// |------------------|---------------------------------------------------------------------------|
// | is_delta         | found by light sampling only, no scattered ray meets it (a point or spot  |
// |                  | lamp of radius 0, a sun of angle 0)                                       |
// | is_hittable_lamp | has a surface outside the BVH that rays meet: intersect() finds it        |
// |                  | (LightSet::lamp_radiance)                                                 |
// | power(R)         | Φ in W, the input of the selection distributions (lights/light_set.h);   |
// |                  | R, the radius of a sphere bounding the scene, sizes lights at infinity    |
// | sample           | next-event estimation: a direction toward the light from the shading     |
// |                  | point p of normal n (unit, or 0 when it has none); triangle_sampling is   |
// |                  | how emissive triangles take their point (lights/light_selection.h)        |
// | sample_emission  | light tracing: a particle leaving the light (lights/emission_sample.h);   |
// |                  | lights at infinity shine over the sphere (center, radius) bounding the    |
// |                  | scene. False when it emits nothing                                        |
// | emits_from_its_centre | sample_emission approximates a lamp with a radius by its centre  |
// | intersect        | the ray (origin, unit dir) meets the lamp's emitting face before t_max:   |
// |                  | distance, radiance toward the origin, and the solid-angle pdf with which  |
// |                  | sample() at the origin picks dir (for MIS)                                |
// | bounds           | the light tree's bound (lights/light_bounds.h): box of the emitting       |
// |                  | points and orientation cone; phi is left 0, LightSet fills in power().    |
// |                  | nullopt for lights at infinity (sun, environment), which the tree leaves  |
// |                  | out and chooses with a fixed probability (LightSet). A hittable lamp's    |
// |                  | box must also hold every point intersect() meets: lamp_radiance finds     |
// |                  | lamps through a BVH of these boxes (lights/lamp_bvh.h)                    |
//
// A light is built from the host's LightParams by its model's entry (LightModel), defined in the
// light's own file and registered by type in lights/light_registry.cpp.
//
// One virtual call per question: per sample or per lamp a ray meets, one indirect call, as the
// std::visit over a closed list of types was, while a light added in its own file needs no change
// here or in LightSet.
#pragma once

#include <memory>
#include <optional>

#include "core/math.h"
#include "lights/emission_sample.h"
#include "lights/light_bounds.h"
#include "lights/light_sample.h"
#include "lights/light_selection.h"
#include "scene/scene.h"

namespace stratum {

class Light {
public:
    virtual ~Light() = default;

    virtual bool is_delta() const = 0;
    virtual bool is_hittable_lamp() const = 0;
    virtual double power(float scene_radius) const = 0;
    virtual bool sample(Vec3 p, Vec3 n, Vec2 u, TriangleSampling triangle_sampling,
                        LightSample* out) const = 0;
    virtual bool sample_emission(Vec2 u_position, Vec2 u_direction, Vec3 center, float radius,
                                 EmissionSample* out) const = 0;
    // sample_emission() starts particles at the centre of a lamp with a radius (its shadows from
    // light paths are hard): the light tracer's notice.
    virtual bool emits_from_its_centre() const { return false; }
    // Lights that are not hittable lamps are met by no ray here (emissive triangles are in the BVH).
    virtual bool intersect(Vec3 /*origin*/, Vec3 /*dir*/, float /*t_max*/, float* /*t*/, Rgb* /*radiance*/,
                           float* /*pdf*/) const {
        return false;
    }
    // A light that does not say where it is counts as one at infinity: chosen outside the tree,
    // with a probability that does not depend on the shading point (never biased, only slower).
    virtual std::optional<LightBounds> bounds() const { return std::nullopt; }
};

// How one light type becomes a light: defined in the light's own file, registered by type in
// lights/light_registry.cpp.
struct LightModel {
    // The light that `params` describe (checked at the C ABI, including by check_own_params).
    std::unique_ptr<Light> (*make)(const LightParams& params);
    // Checks the parameters only this type reads, in `given` as the host passed them, and stores
    // them in *params, whose parameters common to every type are checked already. Throws
    // std::invalid_argument naming the bad value (the C ABI reports it as an invalid argument).
    // Null when the type reads only the common parameters.
    void (*check_own_params)(const LightParams& given, LightParams* params);
};

}  // namespace stratum
