// A closure's parameters as the host describes them (StratumMaterialDesc): the model and its
// inputs. What each model does with them is the BSDF layer's (the registry in bsdf/bsdf.cpp lists
// the models, one line each).
#pragma once

#include <cstdint>

#include "core/math.h"

namespace stratum {

// The Principled node's microfacet distribution (Blender's `distribution`): single-scatter GGX,
// or GGX with multiple-scattering energy compensation (Cycles 4.x "Multiscatter GGX").
enum class MicrofacetDistribution : int32_t { Ggx = 0, MultiscatterGgx = 1 };

// The shadowing term where the shading normal was perturbed (bsdf/bump_shadowing.h):
// the rule each Cycles version applies.
enum class BumpShadowing : int32_t {
    None = 0,
    Chiang = 1,
    ChiangUnsmoothed = 2,
    Conty = 3,
    ContyUnsmoothed = 4
};

struct Material {
    // The C ABI's StratumMaterialModel value: the registry in bsdf/bsdf.cpp names the closure
    // model of each, so this layer lists none of them.
    int32_t model;
    Rgb base_color;
    float roughness;
    float metallic;
    float specular;
    float ior;
    Rgb emission;
    MicrofacetDistribution distribution;
    // Principled transmission and coat (StratumMaterialDesc's appended fields; 0 = none).
    float transmission = 0.0f;
    float coat = 0.0f;
    float coat_roughness = 0.0f;
    float coat_ior = 1.5f;
    Rgb coat_tint{1.0f};
    // The shadowing term where the shading point's normal was perturbed (bsdf/bump_shadowing.h).
    BumpShadowing bump_shadowing = BumpShadowing::None;
    // What a path changes of the closures at one shading point (never the host; Cycles' Light
    // Paths, integrators/light_path_closures.h): Filter Glossy's least alpha of every microfacet
    // lobe (bsdf_blur), and the glossy reflection / refraction lobes the caustics switches drop.
    float min_alpha = 0.0f;
    bool no_glossy_reflection = false, no_glossy_refraction = false;
};

}  // namespace stratum
