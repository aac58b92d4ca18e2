// BSDF interface used by the integrators: one evaluation and one sampling entry point for every
// surface model, dispatching on Material::model. Directions below the shading horizon (wi.z < 0)
// are transmission; only Glass and Transparent produce them.
//
// | model        | meaning                                                   | file              |
// |--------------|-----------------------------------------------------------|-------------------|
// | Diffuse      | Lambert, albedo = base_color                              | lambert.h         |
// | PrincipledV1 | Cycles 3.x Principled: Burley diffuse + GGX, cspec0       | principled_v1.h   |
// | PrincipledV2 | Cycles 4.x Principled: Lambert under a dielectric GGX     | principled_v2.h   |
// |              | layer (energy conserving) + F82 metal                     |                   |
// | Emission     | no scattering (the emitted radiance lives in `emission`)  | bsdf.cpp          |
// | Glossy       | GGX reflection, Fresnel 1, tinted by base_color           | glossy.h          |
// | Glass        | GGX dielectric reflection + refraction at `ior`           | glass.h           |
// | Transparent  | delta pass-through wi = -wo, tinted by base_color         | bsdf.cpp          |
// | Holdout      | no scattering; the integrator turns its weight into alpha | bsdf.cpp          |
//
// Material parameters: roughness is the artist roughness (alpha = roughness^2); `specular` is
// Cycles 3.x "Specular" for V1 and 4.x "Specular IOR Level" for V2 (0.5 keeps `ior` unchanged);
// `ior` is used by V2 only (V1 derives its IOR from `specular`, as Cycles 3.x does).
#pragma once

#include <cstdint>

#include "bsdf/bump_shadowing.h"
#include "core/math.h"
#include "sampling/hemisphere.h"
#include "scene/material.h"

namespace stratum {

// What kind of scattering produced a direction: it selects the ray visibility bit of the next
// ray, the light visibility bit NEE honours, and whether the vertex counts as a bounce.
enum class ScatterKind : uint8_t { Diffuse, Glossy, Transmission, Transparent };

// value = f(wo, wi) |cos theta_i|; pdf = solid-angle density with which bsdf_sample produces wi;
// diffuse = the part of value from diffuse lobes (Lambert, Burley), which bump shadowing scales.
struct BsdfEval {
    Rgb value;
    float pdf;
    Rgb diffuse{};
};

// weight = value / pdf for the sampled wi (the path throughput factor). A delta lobe (smooth
// glass, mirror, transparent) reports delta = true and pdf = 1 by convention: its direction can
// be found by no other strategy, so emission it reaches takes the full MIS weight.
struct BsdfSample {
    Vec3 wi;
    Rgb weight;
    float pdf;
    bool delta = false;
    ScatterKind kind = ScatterKind::Diffuse;
};

// Whether a closure of this model is a Dirac distribution only (it never contributes to NEE).
bool bsdf_is_delta(const Material& m);
// Whether the closure can send light through the surface (NEE must then test lights below it).
bool bsdf_has_transmission(const Material& m);

// wo, wi in the local shading frame (z = shading normal), both pointing away from the surface;
// wo points toward the viewer (wo.z > 0). wi.z < 0 is transmission (0 for opaque models).
// Transmissive models read `ior` as the relative IOR of the side below the horizon over the
// side of wo (the caller inverts it on back faces, as Cycles does with SD_BACKFACING).
// Delta lobes are not part of bsdf_eval (their value is a Dirac; eval gives 0 there).
// `hemisphere` is the distribution diffuse lobes sample directions from (a render setting);
// the pdf reported is always the exact density of that choice, so every choice is unbiased.
BsdfEval bsdf_eval(const Material& m, Vec3 wo, Vec3 wi,
                   HemisphereDistribution hemisphere = HemisphereDistribution::Cosine);
// u_lobe picks the lobe, u warps inside it. Returns false when no direction is produced (absorbed).
bool bsdf_sample(const Material& m, Vec3 wo, float u_lobe, Vec2 u, BsdfSample* out,
                 HemisphereDistribution hemisphere = HemisphereDistribution::Cosine);

}  // namespace stratum
