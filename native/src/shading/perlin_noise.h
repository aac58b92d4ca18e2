// Perlin gradient noise in 1 to 4 dimensions as Cycles evaluates it (kernel/svm/noise.h, itself
// from Open Shading Language): lattice corners hashed by lookup3 (shading/cycles_hash.h), OSL's
// gradient sets, the quintic fade 6t^5 - 15t^4 + 10t^3, multilinear blending, and the per-
// dimension scales (0.25, 0.6616, 0.9820, 0.8344) that bring the result to about [-1, 1].
//
// Two generations of the wrappers (snoise / noise):
//   Finite  (Blender <= 4.1): a non-finite result reads 0.
//   Wrapped (Blender >= 4.2): each coordinate is taken modulo 100000 first, plus 0.5 when its
//           magnitude is >= 1e6 (Cycles' fix for the lost precision of large coordinates); a
//           non-finite coordinate gives NaN.
// Pure functions; used by the Noise, Musgrave and Wave textures (shading/fractal_noise.h).
#pragma once

#include <array>
#include <cstdint>

namespace stratum::perlin {

// A point of N dimensions (1 to 4).
template <int N>
using Point = std::array<float, N>;

enum class Precision : int32_t { Finite = 0, Wrapped = 1 };

// Unscaled Perlin noise (Cycles' perlin_1d ... perlin_4d).
float perlin_1d(float x);
float perlin_2d(float x, float y);
float perlin_3d(float x, float y, float z);
float perlin_4d(float x, float y, float z, float w);

// Signed noise, about [-1, 1] (Cycles' snoise_Nd), and unsigned, 0.5 snoise + 0.5 (noise_Nd).
template <int N>
float snoise(const Point<N>& p, Precision precision);
template <int N>
float noise(const Point<N>& p, Precision precision) {
    return 0.5f * snoise<N>(p, precision) + 0.5f;
}

extern template float snoise<1>(const Point<1>&, Precision);
extern template float snoise<2>(const Point<2>&, Precision);
extern template float snoise<3>(const Point<3>&, Precision);
extern template float snoise<4>(const Point<4>&, Precision);

// Cycles' float_to_int(floorf(x)) without C++'s undefined behaviour out of range: a value
// outside the int range (or NaN) gives INT_MIN, as the x86 conversion Cycles runs on does.
int32_t floor_to_lattice(float x);

}  // namespace stratum::perlin
