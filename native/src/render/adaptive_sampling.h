// Adaptive sampling (issue 16, item 2): a pixel stops taking samples when the estimated error of
// its mean, relative to its brightness, falls under the noise threshold. Settings and error
// measure have the meanings of Cycles' (scene/integrator.cpp get_adaptive_sampling,
// kernel/film/adaptive_sampling.h; Dammertz et al. 2010, §2.1); what differs is when a pixel
// may stop and what its error is.
//
// | quantity              | Cycles                              | Stratum                        |
// |-----------------------|-------------------------------------|--------------------------------|
// | threshold t           | adaptive_threshold; 0: max(0.001,   | the same                       |
// |                       | 1/samples)                          |                                |
// | min samples           | adaptive_min_samples; 0:            | the same, rounded up to a      |
// |                       | max(4, ⌈16/t^0.3⌉)                  | power of two                   |
// | checks                | every 16 samples                    | at power-of-two counts, so a   |
// |                       |                                     | pixel keeps a net's prefix     |
// | pixel error e         | Σ_c |I_c − A_c| / (1e-4 + N(s)),     | √(2/π)·Σ_c σ_c / (1e-4 + N(s)), |
// |                       | A the mean of every other sample    | σ_c film/error_estimate.h      |
// | N(s), s = Σ_c I_c     | √s below 1, s above                 | the same                       |
// | converged             | e < 5t                              | the same                       |
// | neighbourhood         | a pixel next to an unconverged one  | a pixel stops only when its 8  |
// |                       | is unconverged (3×3 box dilation)   | neighbours have converged too  |
//
// For independent samples |I − A| is one draw of a normal of standard deviation σ, whose mean
// is √(2/π)·σ: the factor makes e the same quantity on average, where Cycles' is one draw of it.
// A pixel that stopped does not resume (Cycles' can, one check later): its next samples would
// be a power-of-two round behind the others'.
#pragma once

#include <cstdint>
#include <vector>

#include "film/film.h"
#include "render/render_settings.h"

namespace stratum {

struct AdaptiveSampling {
    bool enabled = false;
    double threshold = 0;      // t, resolved
    uint32_t min_samples = 0;  // resolved: a power of two >= 4

    // The settings' automatic values resolved for a render of `samples` samples.
    static AdaptiveSampling resolve(const AdaptiveSettings& settings, uint32_t samples);
    // Whether pixels are checked when they reach `count` of `total` samples.
    bool checks_at(uint32_t count, uint32_t total) const {
        return enabled && count >= min_samples && (count & (count - 1)) == 0 && count < total;
    }
};

// Cycles' relative error e of a pixel's mean (table above), from its last error estimate.
double relative_error(const Film& film, size_t pixel);

// At a check, after film.estimate_errors(): marks stopped the still-sampling pixels whose own
// error and their neighbours' are under the threshold. `stopped` holds a flag per pixel of the
// film's region; pixels stopped earlier count as converged.
void stop_converged_pixels(const Film& film, const AdaptiveSampling& adaptive, std::vector<uint8_t>& stopped);

}  // namespace stratum
