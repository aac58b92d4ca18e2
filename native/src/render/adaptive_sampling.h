// Adaptive sampling (issue 16, item 2): a pixel stops taking samples when the estimated error of
// its mean, relative to its brightness, falls under the noise threshold (metric relative), or
// when another sample would lower the image's MSE less than one elsewhere (metric mse, below).
// Settings and error measure have the meanings of Cycles' (scene/integrator.cpp
// get_adaptive_sampling, kernel/film/adaptive_sampling.h; Dammertz et al. 2010, §2.1); what
// differs is when a pixel may stop and what its error is.
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
// |                       | A the mean of every other sample    | σ_c = s_c/√n, the pixel's      |
// |                       |                                     | sample spread (film/film.h)    |
// | N(s), s = Σ_c I_c     | √s below 1, s above                 | the same                       |
// | converged             | e < 5t                              | the same                       |
// | neighbourhood         | a pixel next to an unconverged one  | a pixel stops only when its 8  |
// |                       | is unconverged (3×3 box dilation)   | neighbours have converged too  |
//
// For independent samples |I − A| is one draw of a normal of standard deviation σ, whose mean
// is √(2/π)·σ: the factor makes e the same quantity on average, where Cycles' is one draw of it.
// σ is the independent-samples estimate s/√n, not the Error pass's (which scales it by the
// sampler's gain G, film/error_estimate.h): a pixel that stops on an error estimated too low
// keeps its error, and G, measured from prefixes, is low where a pixel's smooth direct light
// hides a slower indirect part. On the Cornell box (64², sobol, max 1024 samples, threshold
// 0.02) stopping on the gain's estimate gave 1.4x the MSE of fixed sampling at equal mean
// samples, stopping on s/√n 0.92x. For the low-discrepancy samplers s/√n overstates the error,
// so their pixels stop later than they could: the safe side.
// The metric mse (adaptive_metric, not Cycles') aims at the image's mean squared error at equal
// time instead. With per-sample spreads σ_i, samples n_i and Σ n_i fixed, Σ σ_i²/n_i is least for
// n_i ∝ σ_i (Lagrange): another sample is worth it while its gain σ_i²/n_i² is above a common
// λ², so a pixel is converged once σ_i ≤ λ n_i (the doubling from n_i to 2 n_i gains σ_i²/(2n_i)
// for n_i samples, the same per-sample rate). Then the image's MSE is λ·mean σ, and λ = t² L̄² /
// mean σ makes t the image's RMS error relative to its mean brightness L̄ (no ×5). σ_i is pooled
// over 3×3 pixels in place of the dilation (adaptive_sampling.cpp). Stopping to equalise the
// pixels' errors (n_i ∝ σ_i², what an absolute threshold does) gains nothing: Σ σ_i²/n_i · Σ n_i
// is then Σ σ_i², as with fixed counts. Measured (64², max 1024 samples, threshold 0.1, equal
// time, fixed sampling's MSE interpolated in log-log): Cornell box 0.31x (random) and 0.53x
// (sobol); Wolf 0.70–0.80x at thresholds 0.02–0.04, where an oracle that knows every σ_i and
// every pixel's cost in rays reaches 0.66x (random) and 0.51x (sobol): Wolf's high-spread pixels
// (the fur) trace 3 rays a sample, its flat background 1.
//
// A pixel that stopped does not resume (Cycles' can, one check later): its next samples would
// be a power-of-two round behind the others'.
//
// Screen-space samplers (zsobol, bluenoise) spread neighbouring pixels' samples jointly: zsobol's
// aligned 2^j × 2^j pixel squares hold nets together (Ahmed & Wonka 2020), which is what makes
// their errors blue noise. A pixel that stops while its neighbours go on leaves its error without
// the neighbours' to cancel against, and the error turns white where counts mix. So for them
// pixels stop in aligned kScreenBlock × kScreenBlock blocks: a block stops when all of its pixels
// may. Measured on zsobol's spectrum test (tests/native/render/test_adaptive_sampling.cpp): with single
// pixels the low-frequency ratio rose from 0.14 (fixed counts) to 0.51 and 0.76 as 12% and 21%
// of the pixels stopped at 4 of 32 samples; with 4 × 4 blocks it is 0.34 and 0.59 (blue noise
// weakened, not lost), and 0.80 when 30% stop at 4 (mean 11 samples).
#pragma once

#include <cstdint>
#include <vector>

#include "film/film.h"
#include "render/render_settings.h"

namespace stratum {

// The side of the aligned pixel blocks the screen-space samplers stop in.
inline constexpr uint32_t kScreenBlock = 4;

struct AdaptiveSampling {
    bool enabled = false;
    AdaptiveMetric metric = AdaptiveMetric::Relative;
    double threshold = 0;      // t, resolved
    uint32_t min_samples = 0;  // resolved: a power of two >= 4
    // Pixels stop in aligned blocks of block × block (the screen-space samplers: kScreenBlock).
    uint32_t block = 1;

    // The settings' automatic values resolved for a render of `samples` samples.
    static AdaptiveSampling resolve(const AdaptiveSettings& settings, uint32_t samples);
    // Whether pixels are checked when they reach `count` of `total` samples.
    bool checks_at(uint32_t count, uint32_t total) const {
        return enabled && count >= min_samples && (count & (count - 1)) == 0 && count < total;
    }
};

// Cycles' relative error e of a pixel's mean (table above), from its last error estimate.
double relative_error(const Film& film, size_t pixel);

// At a check: marks stopped the still-sampling pixels whose own error and their neighbours' are
// under the threshold (whole blocks, when adaptive.block > 1). `stopped` holds a flag per pixel
// of the film's region; pixels stopped earlier count as converged.
void stop_converged_pixels(const Film& film, const AdaptiveSampling& adaptive, std::vector<uint8_t>& stopped);

}  // namespace stratum
