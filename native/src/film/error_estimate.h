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
// | b             | the variance rate: Var(I_m) = C·m^-b (1: independent samples; up to 3:   |
// |               | Owen-scrambled nets on smooth integrands, Owen 1997)                     |
// | ρ = 2^b       | Σd2² / Σd1² over the neighbourhood, clamped to [2, 8]                     |
// | V_P           | (d1²/(ρ − 1) + d2²/(ρ(ρ − 1)))/2: a pixel's prefix estimate of Var(I_P)   |
// | G             | Σ V_P / Σ s²/P over the neighbourhood (channels summed)                   |
// | Var(I_n)      | G·s²/n                                                                   |
// | neighbourhood | the (2·kPoolRadius + 1)² pixels around the pixel                          |
//
// Derivation. I_P = (I_{P/2} + J)/2 with J the mean of the second half; when both halves have
// the same variance (independent samples; the two halves of an Owen-scrambled (0,k,2)-net are
// nets scrambled alike), Cov(I_P, I_{P/2}) = Var(I_P), so
//   E d1² = Var(I_{P/2}) − Var(I_P) = (2^b − 1)·Var(I_P),   E d2² = 2^b·(2^b − 1)·Var(I_P),
// and E d2²/E d1² = 2^b: V_P is unbiased for Var(I_P) from two draws. A pixel's own V_P is
// too noisy to use alone (two draws of a heavy-tailed path-tracing estimate: its median is a
// third of its mean on the Cornell box), so it only measures the gain G, pooled with the
// neighbours', which the pixel's s²/n then carries. For independent samples G → 1; for the
// low-discrepancy samplers G < 1 where their points help. At P = 2 there is no d2: ρ = 2.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "film/pixel_region.h"

namespace stratum {

// The neighbourhoods a pixel's gain G and rate ρ are pooled over: (2r + 1)² pixels.
inline constexpr uint32_t kPoolRadius = 2, kRatePoolRadius = 8;

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

// The gains of every pixel of `region` (rows bottom to top) from their prefix means.
void estimate_pixel_errors(const PixelRegion& region, std::span<const PrefixMeans> prefixes,
                           std::span<PixelErrorEstimate> out);

}  // namespace stratum
