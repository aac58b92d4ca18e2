// The per-pixel error of a pixel's mean, from the means of its nested power-of-two prefixes
// (issue 16, item 1): what the Stratum Error pass shows and adaptive sampling stops on.
//
// Samples of one pixel from a low-discrepancy sequence are not independent, so their sample
// variance s²/n misstates the error of their mean (for Sobol on a smooth integrand, by orders
// of magnitude). Randomised QMC measures the error from replicates; here the replicates are the
// pixel's own prefixes, which every sampler of this library keeps as its best point sets (the
// first 2^k samples of a scrambled (0,2)-sequence are a (0,k,2)-net).
//
// The estimate is the independent-samples one, s²/n with s² the sample variance of the pixel's
// n samples (stable: n − 1 degrees of freedom), times the gain G of the sampler over independent
// samples, measured around the pixel from its prefixes:
//
// | symbol        | meaning                                                                  |
// |---------------|--------------------------------------------------------------------------|
// | P             | the pixel's last power-of-two count (P >= 2)                             |
// | I_m           | mean of the pixel's first m samples, per RGB channel                     |
// | d1, d2        | I_P − I_{P/2} and I_{P/2} − I_{P/4}                                      |
// | model         | Var(I_m) = B/m + A/m³: a part that falls as for independent samples      |
// |               | (high-dimensional paths) and one as for Owen-scrambled nets on smooth    |
// |               | integrands (Owen 1997)                                                   |
// | f             | B/P over E d1² = (8·Σd1² − Σd2²)/(6·Σd1²), pooled over the share         |
// |               | neighbourhood, clamped to [0, 1] (1 without d2)                          |
// | V_P           | a pixel's prefix estimate of Var(I_P): the mean of d1² and               |
// |               | d2²/(2f + 8(1 − f)), times f + (1 − f)/7                                 |
// | G             | Σ V_P / Σ s²/P over the gain neighbourhood (channels summed)             |
// | Var(I_n)      | G·s²/n                                                                   |
//
// Derivation. I_P = (I_{P/2} + J)/2 with J the mean of the second half; when both halves have
// the same variance (independent samples; the two halves of an Owen-scrambled (0,k,2)-net are
// nets scrambled alike), Cov(I_P, I_{P/2}) = Var(I_P), so E d1² = Var(I_{P/2}) − Var(I_P). Under
// the model, E d1² = B/P + 7A/P³ and E d2² = 2B/P + 56A/P³, so B/P = (8·E d1² − E d2²)/6, and
// Var(I_P) = B/P + A/P³ = E d1²·(f + (1 − f)/7); E d2² = E d1²·(2f + 8(1 − f)) makes d2 a
// second draw. Independent samples have f = 1 and V_P = E d1² = σ²/P. A single rate (one power
// law) fitted to the two differences would take the steeper, coarser one for the finest level
// and understate a pixel whose smooth direct light hides a slower indirect part. A pixel's own
// V_P is too noisy to use alone (two draws of a heavy-tailed path-tracing estimate: its median
// is a third of its mean on the Cornell box), so it only measures the gain G, pooled with the
// neighbours', which the pixel's s²/n then carries. For independent samples G → 1; for the
// low-discrepancy samplers G < 1 where their points help.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "film/pixel_region.h"

namespace stratum {

// The neighbourhoods a pixel's gain G and share f are pooled over: (2r + 1)² pixels.
inline constexpr uint32_t kPoolRadius = 2, kSharePoolRadius = 8;

// A pixel's prefix means I_P, I_{P/2}, I_{P/4} (RGB each) at its last power-of-two count P, and
// the independent-samples estimate s²/P of Var(I_P) (levels < 2: no estimate).
struct PrefixMeans {
    double mean[3][3] = {};   // [level][channel]: level 0 is I_P
    double iid_variance = 0;  // s²/P, channels summed
    uint32_t count = 0;       // P
    uint32_t levels = 0;      // the levels held: 2 (I_P, I_{P/2}) or 3
};

// A pixel's gain G (count 0: no estimate, G = 1).
struct PixelErrorEstimate {
    float gain = 1.0f;
    uint32_t count = 0;  // P
};

// Sums of v (width × height, row-major) over each pixel's (2r+1)² window, cut at the edges: the
// pooling of the gains here and of the spreads of adaptive sampling's metric mse.
std::vector<double> box_sum(const std::vector<double>& v, uint32_t width, uint32_t height, uint32_t r);

// The gains of every pixel of `region` (rows bottom to top) from their prefix means.
void estimate_pixel_errors(const PixelRegion& region, std::span<const PrefixMeans> prefixes,
                           std::span<PixelErrorEstimate> out);

}  // namespace stratum
