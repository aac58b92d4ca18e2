// lookup3 (cycles_hash.h) over arrays of keys, lane by lane: the very integers of hash_uint3 and
// hash_uint4, laid out as loops over independent lanes so that the compiler runs four lanes per
// instruction (SSE2's 32-bit adds, xors and shifts; no wider instruction set is assumed). Perlin
// noise hashes a cell's 8 corners this way, Voronoi the 27 cells around a point.
#pragma once

#include <cstdint>

#include "shading/cycles_hash.h"

namespace stratum::cycles_hash {

// out[i] = hash_uint3(x[i], y[i], z[i]) for i < L.
template <int L>
inline void hash_uint3_lanes(const uint32_t* x, const uint32_t* y, const uint32_t* z, uint32_t* out) {
    for (int i = 0; i < L; ++i) {
        uint32_t a = seed(3) + x[i], b = seed(3) + y[i], c = seed(3) + z[i];
        finish(a, b, c);
        out[i] = c;
    }
}

// out[i] = hash_uint4(x[i], y[i], z[i], w) for i < L (one w for every lane).
template <int L>
inline void hash_uint4_lanes(const uint32_t* x, const uint32_t* y, const uint32_t* z, uint32_t w,
                             uint32_t* out) {
    for (int i = 0; i < L; ++i) {
        uint32_t a = seed(4) + x[i], b = seed(4) + y[i], c = seed(4) + z[i];
        mix(a, b, c);
        a += w;
        finish(a, b, c);
        out[i] = c;
    }
}

}  // namespace stratum::cycles_hash
