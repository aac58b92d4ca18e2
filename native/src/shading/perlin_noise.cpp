// Perlin noise as Cycles' kernel/svm/noise.h computes it; see perlin_noise.h. The scalar
// formulas of Cycles' non-SIMD path are used (its SSE/AVX paths blend the same corners in the
// same order with a + t (b - a) or fused multiply-adds, a few ulp apart).
#include "shading/perlin_noise.h"

#include <bit>
#include <cmath>
#include <limits>

#include "shading/cycles_hash.h"
#include "shading/cycles_hash_lanes.h"

namespace stratum::perlin {

namespace {

using cycles_hash::hash_uint;
using cycles_hash::hash_uint2;
using cycles_hash::hash_uint4;

float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }
float flip(float v, uint32_t negate) { return negate ? -v : v; }
float lerp(float a, float b, float t) { return a + t * (b - a); }

// OSL's gradient sets: 1D slopes +-1..8, 2D eight directions, 3D twelve cube edges (four
// repeated), 4D thirty-two.
float grad1(uint32_t hash, float x) {
    const uint32_t h = hash & 15u;
    return flip(static_cast<float>(1u + (h & 7u)), h & 8u) * x;
}
float grad2(uint32_t hash, float x, float y) {
    const uint32_t h = hash & 7u;
    const float u = h < 4 ? x : y;
    const float v = 2.0f * (h < 4 ? y : x);
    return flip(u, h & 1u) + flip(v, h & 2u);
}
float grad4(uint32_t hash, float x, float y, float z, float w) {
    const uint32_t h = hash & 31u;
    const float u = h < 24 ? x : y;
    const float v = h < 16 ? y : z;
    const float s = h < 8 ? z : w;
    return flip(u, h & 1u) + flip(v, h & 2u) + flip(s, h & 4u);
}

// The 3D gradient with selects and sign flips on the bits, which the compiler runs four lanes
// at a time (a flip of the sign bit is the negation).
float grad3(uint32_t hash, float x, float y, float z) {
    const uint32_t h = hash & 15u;
    const uint32_t bx = std::bit_cast<uint32_t>(x), by = std::bit_cast<uint32_t>(y);
    const uint32_t bz = std::bit_cast<uint32_t>(z);
    // u = h < 8 ? x : y; v = h < 4 ? y : (h is 12 or 14 ? x : z), as all-ones or all-zero masks.
    const uint32_t below8 = 0u - static_cast<uint32_t>(h < 8u), below4 = 0u - static_cast<uint32_t>(h < 4u);
    const uint32_t is12or14 = 0u - static_cast<uint32_t>((h | 2u) == 14u);
    const uint32_t u = (bx & below8) | (by & ~below8);
    const uint32_t v = (by & below4) | (~below4 & ((bx & is12or14) | (bz & ~is12or14)));
    return std::bit_cast<float>(u ^ ((h & 1u) << 31)) + std::bit_cast<float>(v ^ ((h & 2u) << 30));
}

// Corners v0 (0,0), v1 (1,0), v2 (0,1), v3 (1,1); x then y.
float bilinear(float v0, float v1, float v2, float v3, float x, float y) {
    const float x1 = 1.0f - x;
    return (1.0f - y) * (v0 * x1 + v1 * x) + y * (v2 * x1 + v3 * x);
}
// v0..v3 the z = 0 face as bilinear(), v4..v7 the z = 1 face.
float trilinear(const float* v, float x, float y, float z) {
    const float x1 = 1.0f - x, y1 = 1.0f - y, z1 = 1.0f - z;
    return z1 * (y1 * (v[0] * x1 + v[1] * x) + y * (v[2] * x1 + v[3] * x)) +
           z * (y1 * (v[4] * x1 + v[5] * x) + y * (v[6] * x1 + v[7] * x));
}

// The lattice cell of x and the offset in it (Cycles' floorfrac).
float cell(float x, uint32_t& lattice) {
    const float f = std::floor(x);
    lattice = static_cast<uint32_t>(floor_to_lattice(f));
    return x - f;
}

float wrap(float p, Precision precision) {
    if (precision == Precision::Finite) return p;
    const float correction = std::fabs(p) >= 1000000.0f ? 0.5f : 0.0f;
    return std::fmod(p, 100000.0f) + correction;
}

constexpr float kScale[5] = {0.0f, 0.2500f, 0.6616f, 0.9820f, 0.8344f};

}  // namespace

int32_t floor_to_lattice(float x) {
    // The float range that converts exactly: [-2^31, 2^31).
    if (x >= -2147483648.0f && x < 2147483648.0f) return static_cast<int32_t>(x);
    return std::numeric_limits<int32_t>::min();
}

float perlin_1d(float x) {
    uint32_t X;
    const float fx = cell(x, X);
    const float u = fade(fx);
    return lerp(grad1(hash_uint(X), fx), grad1(hash_uint(X + 1u), fx - 1.0f), u);
}

float perlin_2d(float x, float y) {
    uint32_t X, Y;
    const float fx = cell(x, X), fy = cell(y, Y);
    return bilinear(grad2(hash_uint2(X, Y), fx, fy), grad2(hash_uint2(X + 1u, Y), fx - 1.0f, fy),
                    grad2(hash_uint2(X, Y + 1u), fx, fy - 1.0f),
                    grad2(hash_uint2(X + 1u, Y + 1u), fx - 1.0f, fy - 1.0f), fade(fx), fade(fy));
}

float perlin_3d(float x, float y, float z) {
    uint32_t X, Y, Z;
    const float fx = cell(x, X), fy = cell(y, Y), fz = cell(z, Z);
    // The corners' hashes first, all eight at once (cycles_hash_lanes.h), then their gradients.
    uint32_t kx[8], ky[8], kz[8], hash[8];
    for (uint32_t corner = 0; corner < 8; ++corner) {
        kx[corner] = X + (corner & 1u);
        ky[corner] = Y + ((corner >> 1) & 1u);
        kz[corner] = Z + ((corner >> 2) & 1u);
    }
    cycles_hash::hash_uint3_lanes<8>(kx, ky, kz, hash);
    constexpr float kLow[8] = {0, 1, 0, 1, 0, 1, 0, 1}, kMid[8] = {0, 0, 1, 1, 0, 0, 1, 1};
    constexpr float kHigh[8] = {0, 0, 0, 0, 1, 1, 1, 1};
    float v[8];
    for (int corner = 0; corner < 8; ++corner)
        v[corner] = grad3(hash[corner], fx - kLow[corner], fy - kMid[corner], fz - kHigh[corner]);
    return trilinear(v, fade(fx), fade(fy), fade(fz));
}

float perlin_4d(float x, float y, float z, float w) {
    uint32_t X, Y, Z, W;
    const float fx = cell(x, X), fy = cell(y, Y), fz = cell(z, Z), fw = cell(w, W);
    float v[16];
    for (uint32_t corner = 0; corner < 16; ++corner) {
        const uint32_t dx = corner & 1u, dy = (corner >> 1) & 1u, dz = (corner >> 2) & 1u;
        const uint32_t dw = (corner >> 3) & 1u;
        v[corner] =
            grad4(hash_uint4(X + dx, Y + dy, Z + dz, W + dw), fx - static_cast<float>(dx),
                  fy - static_cast<float>(dy), fz - static_cast<float>(dz), fw - static_cast<float>(dw));
    }
    const float u = fade(fx), t = fade(fy), s = fade(fz);
    return lerp(trilinear(v, u, t, s), trilinear(v + 8, u, t, s), fade(fw));
}

template <int N>
float snoise(const Point<N>& p, Precision precision) {
    Point<N> q;
    for (int i = 0; i < N; ++i) q[i] = wrap(p[i], precision);
    float r;
    if constexpr (N == 1) r = perlin_1d(q[0]);
    if constexpr (N == 2) r = perlin_2d(q[0], q[1]);
    if constexpr (N == 3) r = perlin_3d(q[0], q[1], q[2]);
    if constexpr (N == 4) r = perlin_4d(q[0], q[1], q[2], q[3]);
    if (precision == Precision::Finite && !std::isfinite(r)) r = 0.0f;
    return kScale[N] * r;
}

template float snoise<1>(const Point<1>&, Precision);
template float snoise<2>(const Point<2>&, Precision);
template float snoise<3>(const Point<3>&, Precision);
template float snoise<4>(const Point<4>&, Precision);

}  // namespace stratum::perlin
