// Fractal sums of Perlin noise (shading/perlin_noise.h) as Cycles builds its Noise and Musgrave
// textures: fBM, multifractal, hybrid multifractal, ridged multifractal and heterogeneous terrain
// (kernel/svm/fractal_noise.h at v3.4.0 and v5.0.0, kernel/svm/musgrave.h at v3.4.0; the
// multifractals are Musgrave's, "Texturing and Modeling: A Procedural Approach").
//
// Octaves: the Noise texture sums int(detail) + 1 whole octaves, the Musgrave texture
// int(detail); both then add the fraction detail - floor(detail) of one more. Callers clamp
// detail to [0, 15] first (as Cycles does), so at most 16 octaves are summed. Each octave
// multiplies the frequency by `lacunarity` and the amplitude by `roughness` (Musgrave's
// lacunarity^-dimension). Pure functions, N = 1..4 dimensions.
#pragma once

#include "shading/perlin_noise.h"

namespace stratum::fractal {

using perlin::Point;
using perlin::Precision;

// How many octaves: `whole` full ones, then `fraction` of one more.
struct Octaves {
    int whole;
    float fraction;
};
// The Noise texture's (Blender 3.x to 5.x): int(detail) + 1 whole octaves.
Octaves noise_octaves(float detail);
// The Musgrave texture's (Blender 3.x, 4.0): int(detail) whole octaves.
Octaves musgrave_octaves(float detail);

// Blender 3.x's Noise texture: fBM of unsigned noise, normalised to [0, 1], lacunarity 2,
// roughness clamped to [0, 1] (its fractal_noise_Nd).
template <int N>
float fbm_3x(const Point<N>& p, float detail, float roughness);

// Blender 4.x/5.x's Noise fBM: signed noise; `normalize` maps to [0, 1] (the normalised sum as
// 3.x's, rounded differently). Blender 4.0 clamps roughness to [0, 1] before calling; 4.1+ to
// >= 0.
template <int N>
float fbm(const Point<N>& p, float detail, float roughness, float lacunarity, bool normalize,
          Precision precision);

// Blender 3.x's Musgrave fBM: the sum of signed octaves, not normalised.
template <int N>
float musgrave_fbm(Point<N> p, Octaves octaves, float roughness, float lacunarity);

// The multifractals, shared by Noise (4.1+) and Musgrave: the product of (1 + amplitude x noise);
// terrains raised by `offset`; hybrid and ridged weigh each octave by `gain` times the last.
template <int N>
float multifractal(Point<N> p, Octaves octaves, float roughness, float lacunarity, Precision precision);
template <int N>
float hetero_terrain(Point<N> p, Octaves octaves, float roughness, float lacunarity, float offset,
                     Precision precision);
template <int N>
float hybrid_multifractal(Point<N> p, Octaves octaves, float roughness, float lacunarity, float offset,
                          float gain, Precision precision);
template <int N>
float ridged_multifractal(Point<N> p, Octaves octaves, float roughness, float lacunarity, float offset,
                          float gain, Precision precision);

// Cycles' clamp (min(max(a, lo), hi) with a > b ? a : b), which maps NaN to lo.
inline float cycles_clamp(float a, float lo, float hi) {
    const float m = a > lo ? a : lo;
    return m < hi ? m : hi;
}

}  // namespace stratum::fractal
