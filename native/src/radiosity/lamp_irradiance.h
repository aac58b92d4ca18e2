// Lamps pre-converted to each patch's direct irradiance (textbook §3: a point light gives
// κ I c_x / r², a parallel light κ E c_x; here every lamp kind, by its own light sampling).
//
// | quantity   | definition |
// |------------|------------|
// | lamps      | the LightSet's lights that are neither emissive triangles (those are patches, with |
// |            | emission M_e) nor the environment (the form-factor rays' sky term), and whose |
// |            | visibility lights diffuse closures (StratumVisibility DIFFUSE) |
// | E_i        | (1/S) Σ_s L_s c_s v_s / (p_s P(l_s)), S = kLampSamples points per patch |
// | point s    | uniform on the patch (sobol pair 0 of sample s at "pixel" (i mod 2^16, i / 2^16), seed |
// |            | kLampSeed), lamp l_s chosen with probability P(l) ∝ its power (dimension 4; uniform |
// |            | when every power is 0), the lamp's own sample (Light::sample) from pair 2 |
// | v_s        | a shadow ray from the point to the lamp sample, unless the lamp casts no shadow |
//
// For a point lamp of radius 0 and intensity I, Light::sample gives L_s = I/r² at normal
// incidence with p_s = 1, so E_i is the patch average of I c/r² v over 16 points: the book's
// κ I c_x / r² (the solver multiplies by κ), integrated over the patch rather than taken at
// its centre, so a shadow edge across a patch gives the covered share. A sun gives E c_x v.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "radiosity/patch_set.h"
#include "render_scene/render_scene.h"

namespace stratum {

inline constexpr uint32_t kLampSamples = 16;
inline constexpr uint32_t kLampSeed = 0x52414432u;  // "RAD2"

struct LampIrradiance {
    std::vector<Rgb> irradiance;  // per patch; empty when the scene has no lamp
    uint64_t rays = 0;
};

// The lamps as the header defines them (indices into scene.lights()).
std::vector<uint32_t> radiosity_lamps(const RenderScene& scene);

// Throws RenderScene::BuildCancelled when *cancel (may be null) becomes true.
LampIrradiance lamp_irradiance(const RenderScene& scene, const PatchSet& patches,
                               const std::atomic<bool>* cancel);

}  // namespace stratum
