// Void-and-cluster dither arrays (Ulichney 1993, "The void-and-cluster method for dither array
// generation", Proc. SPIE 1913). Pure math: a deterministic function of its arguments.
//
// | parameter        | value used by `bluenoise`                         |
// |------------------|---------------------------------------------------|
// | size             | 128 (a 128 × 128 torus, 16384 ranks)              |
// | sigma            | 1.5 texels (Ulichney's σ)                         |
// | initial fraction | 10 % ones, placed by PCG32(seed)                  |
//
// Energy of a texel = Σ over the "ones" of exp(−r²/(2σ²)), r the toroidal (minimum-image)
// distance. The tightest cluster is the one with the highest energy, the largest void the zero
// with the lowest; ties go to the lowest row-major index.
//  0. initial binary pattern: the random ones are relaxed by repeatedly moving the tightest
//     cluster to the largest void until the void found is the cluster just removed;
//  1. phase 1: from that prototype, remove the tightest cluster and give it the next rank
//     downwards (m − 1 .. 0);
//  2. phases 2 and 3: from the prototype, fill the largest void and give it the next rank
//     upwards (m .. size² − 1). Ulichney's phase 3 (past half, fill the tightest cluster of
//     zeros, measured with the zeros' energy) is the same choice: over a whole torus the kernel
//     sums to the same constant K at every texel, so zeros' energy = K − ones' energy, and its
//     maximum over zeros is the ones' energy minimum over zeros.
// The energy array is updated incrementally (± one kernel, which separates into a product of
// two 1D Gaussians) when a one is added or removed: O(size²) per step, O(size⁴) in all.
#pragma once

#include <cstdint>
#include <vector>

namespace stratum::void_and_cluster {

// The rank of every texel, row-major (texel (x, y) at y·size + x): a permutation of
// [0, size²). size ≥ 2.
std::vector<uint32_t> rank_texture(uint32_t size, double sigma, double initial_fraction, uint64_t seed);

// The toroidal Gaussian energy of a binary pattern (row-major, nonzero = one), recomputed from
// scratch: the reference the incremental update is tested against.
std::vector<double> energy(const std::vector<uint8_t>& pattern, uint32_t size, double sigma);

}  // namespace stratum::void_and_cluster
