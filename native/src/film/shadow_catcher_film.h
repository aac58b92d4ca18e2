// Cycles' shadow catcher at read-out: the Shadow Catcher pass and what Combined shows when the
// scene has a catcher (Cycles 3.4 / 5.0 kernel/film/read.h film_calculate_shadow_catcher and
// film_calculate_shadow_catcher_matte_with_shadow; session/buffers.cpp get_actual_display_pass).
// The integrator's side, the split of a camera path, is integrators/shadow_catcher.h.
//
// | sum (per camera sample) | value                                                            |
// |-------------------------|------------------------------------------------------------------|
// | 0..2   catcher          | light of the catcher-only copy of the path (PASS_SHADOW_CATCHER) |
// | 3..5   matte            | light written while the path had not split (..._MATTE rgb)       |
// | 6      matte transp.    | transparency of the unsplit path, + the throughput at the split  |
// | 7      split            | 1 when the path split (PASS_SHADOW_CATCHER_SAMPLE_COUNT)         |
// | 8..10  background       | background along the camera ray, of misses and at the split      |
// |                         | (Cycles' Background pass, which the copy writes at the split)    |
//
// | read-out (means over the pixel's samples)  | value                                        |
// |--------------------------------------------|----------------------------------------------|
// | ratio r (per channel)                      | 1 if no sample split; else (C − M)/K, 1 where K = 0 |
// | Shadow Catcher pass                        | (1 − α_C)·1 + α_C·r, α_C = Combined's alpha  |
// | Combined, Matte (the pass is asked for)    | (M, sat(1 − T))                              |
// | Combined, MatteWithShadow (transparent)    | (M, a), a = (1 − α)(1 − sat(mean r)) + α, α = sat(1 − T) |
// | Combined, MatteWithShadowOverBackground    | (M + B (1 − a), 1)                           |
#pragma once

#include <algorithm>
#include <array>

#include "core/math.h"
#include "film/passes.h"

namespace stratum {

// One camera sample's values of the sums above.
struct ShadowCatcherSample {
    Rgb catcher{0.0f};
    Rgb matte{0.0f};
    float matte_transparency = 0.0f;
    float split = 0.0f;
    Rgb background{0.0f};

    std::array<float, kShadowCatcherSums> values() const {
        return {catcher.r,          catcher.g, catcher.b,    matte.r,      matte.g,     matte.b,
                matte_transparency, split,     background.r, background.g, background.b};
    }
};

// What Combined shows in a scene with a shadow catcher (Off: one without, or an integrator that
// does not split paths). Cycles: Matte when the Shadow Catcher pass is asked for; else the
// approximate matte with shadow, over the Background pass when the film is not transparent.
enum class CatcherCombined : uint8_t { Off, Matte, MatteWithShadow, MatteWithShadowOverBackground };

// Cycles' safe_divide_shadow_catcher and film_calculate_shadow_catcher: `m` are the means of the
// sums above, `combined` Combined's RGB mean and `alpha` its alpha.
inline Rgb shadow_catcher_pass(Rgb combined, float alpha, const double* m) {
    if (m[7] == 0.0) return Rgb(1.0f);
    const auto ratio = [](double without_matte, double catcher) {
        return catcher != 0.0 ? static_cast<float>(without_matte / catcher) : 1.0f;
    };
    const Rgb r(ratio(combined.r - m[3], m[0]), ratio(combined.g - m[4], m[1]),
                ratio(combined.b - m[5], m[2]));
    const float a = std::clamp(alpha, 0.0f, 1.0f);
    return Rgb(1.0f - a) + r * a;
}

// Combined's RGBA in a scene with a catcher; `pass` is shadow_catcher_pass's value.
inline std::array<float, 4> matte_combined(CatcherCombined mode, Rgb pass, const double* m) {
    const float mr = static_cast<float>(m[3]), mg = static_cast<float>(m[4]), mb = static_cast<float>(m[5]);
    const float alpha = std::clamp(1.0f - static_cast<float>(m[6]), 0.0f, 1.0f);
    if (mode == CatcherCombined::Matte) return {mr, mg, mb, alpha};
    const float matte_alpha = (1.0f - alpha) * (1.0f - std::clamp(pass.average(), 0.0f, 1.0f)) + alpha;
    if (mode == CatcherCombined::MatteWithShadow) return {mr, mg, mb, matte_alpha};
    const float cover = 1.0f - matte_alpha;
    return {mr + static_cast<float>(m[8]) * cover, mg + static_cast<float>(m[9]) * cover,
            mb + static_cast<float>(m[10]) * cover, 1.0f};
}

}  // namespace stratum
