// Fractal noise sums; see fractal_noise.h. Each function keeps Cycles' order of operations
// (the frequency kept as a running scale in fBM, as a running point in the multifractals), so
// the floats round as Cycles' do.
#include "shading/fractal_noise.h"

#include <cmath>

namespace stratum::fractal {

namespace {

using perlin::noise;
using perlin::snoise;

template <int N>
Point<N> scaled(const Point<N>& p, float s) {
    Point<N> q;
    for (int i = 0; i < N; ++i) q[i] = s * p[i];
    return q;
}
template <int N>
void scale_in_place(Point<N>& p, float s) {
    for (int i = 0; i < N; ++i) p[i] *= s;
}
float lerp(float a, float b, float t) { return a + t * (b - a); }

}  // namespace

Octaves noise_octaves(float detail) {
    const float d = cycles_clamp(detail, 0.0f, 15.0f);
    return {static_cast<int>(d) + 1, d - std::floor(d)};
}

Octaves musgrave_octaves(float detail) {
    const float d = cycles_clamp(detail, 0.0f, 15.0f);
    return {static_cast<int>(d), d - std::floor(d)};
}

template <int N>
float fbm_3x(const Point<N>& p, float detail, float roughness) {
    const Octaves octaves = noise_octaves(detail);
    const float r = cycles_clamp(roughness, 0.0f, 1.0f);
    float fscale = 1.0f, amp = 1.0f, maxamp = 0.0f, sum = 0.0f;
    for (int i = 0; i < octaves.whole; ++i) {
        sum += noise<N>(scaled<N>(p, fscale), Precision::Finite) * amp;
        maxamp += amp;
        amp *= r;
        fscale *= 2.0f;
    }
    const float rmd = octaves.fraction;
    if (rmd == 0.0f) return sum / maxamp;
    const float sum2 = sum + noise<N>(scaled<N>(p, fscale), Precision::Finite) * amp;
    return (1.0f - rmd) * (sum / maxamp) + rmd * (sum2 / (maxamp + amp));
}

template <int N>
float fbm(const Point<N>& p, float detail, float roughness, float lacunarity, bool normalize,
          Precision precision) {
    const Octaves octaves = noise_octaves(detail);
    float fscale = 1.0f, amp = 1.0f, maxamp = 0.0f, sum = 0.0f;
    for (int i = 0; i < octaves.whole; ++i) {
        sum += snoise<N>(scaled<N>(p, fscale), precision) * amp;
        maxamp += amp;
        amp *= roughness;
        fscale *= lacunarity;
    }
    const float rmd = octaves.fraction;
    if (rmd == 0.0f) return normalize ? 0.5f * sum / maxamp + 0.5f : sum;
    const float sum2 = sum + snoise<N>(scaled<N>(p, fscale), precision) * amp;
    return normalize ? lerp(0.5f * sum / maxamp + 0.5f, 0.5f * sum2 / (maxamp + amp) + 0.5f, rmd)
                     : lerp(sum, sum2, rmd);
}

template <int N>
float musgrave_fbm(Point<N> p, Octaves octaves, float roughness, float lacunarity) {
    float value = 0.0f, pwr = 1.0f;
    for (int i = 0; i < octaves.whole; ++i) {
        value += snoise<N>(p, Precision::Finite) * pwr;
        pwr *= roughness;
        scale_in_place<N>(p, lacunarity);
    }
    if (octaves.fraction != 0.0f) value += octaves.fraction * snoise<N>(p, Precision::Finite) * pwr;
    return value;
}

template <int N>
float multifractal(Point<N> p, Octaves octaves, float roughness, float lacunarity, Precision precision) {
    float value = 1.0f, pwr = 1.0f;
    for (int i = 0; i < octaves.whole; ++i) {
        value *= pwr * snoise<N>(p, precision) + 1.0f;
        pwr *= roughness;
        scale_in_place<N>(p, lacunarity);
    }
    if (octaves.fraction != 0.0f) value *= octaves.fraction * pwr * snoise<N>(p, precision) + 1.0f;
    return value;
}

template <int N>
float hetero_terrain(Point<N> p, Octaves octaves, float roughness, float lacunarity, float offset,
                     Precision precision) {
    float pwr = roughness;
    // The first octave unscaled, the later ones scaled by the value so far.
    float value = offset + snoise<N>(p, precision);
    scale_in_place<N>(p, lacunarity);
    for (int i = 1; i < octaves.whole; ++i) {
        value += (snoise<N>(p, precision) + offset) * pwr * value;
        pwr *= roughness;
        scale_in_place<N>(p, lacunarity);
    }
    if (octaves.fraction != 0.0f) {
        const float increment = (snoise<N>(p, precision) + offset) * pwr * value;
        value += octaves.fraction * increment;
    }
    return value;
}

template <int N>
float hybrid_multifractal(Point<N> p, Octaves octaves, float roughness, float lacunarity, float offset,
                          float gain, Precision precision) {
    float pwr = 1.0f, value = 0.0f, weight = 1.0f;
    for (int i = 0; weight > 0.001f && i < octaves.whole; ++i) {
        weight = std::fmin(weight, 1.0f);
        const float signal = (snoise<N>(p, precision) + offset) * pwr;
        pwr *= roughness;
        value += weight * signal;
        weight *= gain * signal;
        scale_in_place<N>(p, lacunarity);
    }
    if (octaves.fraction != 0.0f && weight > 0.001f) {
        weight = std::fmin(weight, 1.0f);
        const float signal = (snoise<N>(p, precision) + offset) * pwr;
        value += octaves.fraction * weight * signal;
    }
    return value;
}

template <int N>
float ridged_multifractal(Point<N> p, Octaves octaves, float roughness, float lacunarity, float offset,
                          float gain, Precision precision) {
    // Cycles sums whole octaves only here: the fraction is ignored.
    float pwr = roughness;
    float signal = offset - std::fabs(snoise<N>(p, precision));
    signal *= signal;
    float value = signal, weight = 1.0f;
    for (int i = 1; i < octaves.whole; ++i) {
        scale_in_place<N>(p, lacunarity);
        weight = cycles_clamp(signal * gain, 0.0f, 1.0f);
        signal = offset - std::fabs(snoise<N>(p, precision));
        signal *= signal;
        signal *= weight;
        value += signal * pwr;
        pwr *= roughness;
    }
    return value;
}

#define STRATUM_FRACTAL_INSTANTIATE(N)                                                               \
    template float fbm_3x<N>(const Point<N>&, float, float);                                         \
    template float fbm<N>(const Point<N>&, float, float, float, bool, Precision);                    \
    template float musgrave_fbm<N>(Point<N>, Octaves, float, float);                                 \
    template float multifractal<N>(Point<N>, Octaves, float, float, Precision);                      \
    template float hetero_terrain<N>(Point<N>, Octaves, float, float, float, Precision);             \
    template float hybrid_multifractal<N>(Point<N>, Octaves, float, float, float, float, Precision); \
    template float ridged_multifractal<N>(Point<N>, Octaves, float, float, float, float, Precision);
STRATUM_FRACTAL_INSTANTIATE(1)
STRATUM_FRACTAL_INSTANTIATE(2)
STRATUM_FRACTAL_INSTANTIATE(3)
STRATUM_FRACTAL_INSTANTIATE(4)
#undef STRATUM_FRACTAL_INSTANTIATE

}  // namespace stratum::fractal
