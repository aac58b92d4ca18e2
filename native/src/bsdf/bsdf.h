// BSDF interface used by the integrators: one evaluation and one sampling entry point for every
// surface model, dispatching on Material::model. Reflection only for now (no transmission).
//
// | model        | meaning                                                   | file              |
// |--------------|-----------------------------------------------------------|-------------------|
// | Diffuse      | Lambert, albedo = base_color                              | lambert.h         |
// | PrincipledV1 | Cycles 3.x Principled: Burley diffuse + GGX, cspec0       | principled_v1.h   |
// | PrincipledV2 | Cycles 4.x Principled: Lambert under a dielectric GGX     | principled_v2.h   |
// |              | layer (energy conserving) + F82 metal                     |                   |
// | Emission     | no scattering (the emitted radiance lives in `emission`)  | bsdf.cpp          |
//
// Material parameters: roughness is the artist roughness (alpha = roughness^2); `specular` is
// Cycles 3.x "Specular" for V1 and 4.x "Specular IOR Level" for V2 (0.5 keeps `ior` unchanged);
// `ior` is used by V2 only (V1 derives its IOR from `specular`, as Cycles 3.x does).
#pragma once

#include <cstdint>

#include "core/math.h"
#include "sampling/hemisphere.h"

namespace stratum {

enum class MaterialModel : int32_t { Diffuse = 0, PrincipledV1 = 1, PrincipledV2 = 2, Emission = 3 };

// The Principled node's microfacet distribution (Blender's `distribution`): single-scatter GGX,
// or GGX with multiple-scattering energy compensation (Cycles 4.x "Multiscatter GGX").
enum class MicrofacetDistribution : int32_t { Ggx = 0, MultiscatterGgx = 1 };

struct Material {
    MaterialModel model;
    Rgb base_color;
    float roughness;
    float metallic;
    float specular;
    float ior;
    Rgb emission;
    MicrofacetDistribution distribution;
};

// value = f(wo, wi) |cos theta_i|; pdf = solid-angle density with which bsdf_sample produces wi.
struct BsdfEval {
    Rgb value;
    float pdf;
};

// weight = value / pdf for the sampled wi (the path throughput factor).
struct BsdfSample {
    Vec3 wi;
    Rgb weight;
    float pdf;
};

// wo, wi in the local shading frame (z = shading normal), both pointing away from the surface;
// wo points toward the viewer. A wi or wo below the horizon gives value 0.
// `hemisphere` is the distribution diffuse lobes sample directions from (a render setting);
// the pdf reported is always the exact density of that choice, so every choice is unbiased.
BsdfEval bsdf_eval(const Material& m, Vec3 wo, Vec3 wi,
                   HemisphereDistribution hemisphere = HemisphereDistribution::Cosine);
// u_lobe picks the lobe, u warps inside it. Returns false when no direction is produced (absorbed).
bool bsdf_sample(const Material& m, Vec3 wo, float u_lobe, Vec2 u, BsdfSample* out,
                 HemisphereDistribution hemisphere = HemisphereDistribution::Cosine);

}  // namespace stratum
