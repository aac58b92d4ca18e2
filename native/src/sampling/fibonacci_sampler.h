// `fibonacci` / `fibonacci_static`: the Fibonacci lattice of seed 000 (eq. 19; table 3) over the
// spp points of every dimension pair, randomised by a toroidal (Cranley–Patterson) shift.
//
// | parameter | meaning                                                                     |
// |-----------|-----------------------------------------------------------------------------|
// | samples   | n = spp: the lattice size                                                   |
// | lattice   | point j: ((j + 1)/φ mod 1, (j + 0.5)/n), φ = (1 + √5)/2, j = 0..n−1 (eq. 19  |
// |           | as printed in seed 000, which writes i = 0..n: n + 1 indices for n points)  |
// | shift     | fibonacci: per (pixel, pair, seed), uniform on the torus — the seed's        |
// |           | "random per-pixel seed" (a random rotation of the lattice);                  |
// |           | fibonacci_static: per (pair, seed) only, the same in every pixel — the       |
// |           | "static seed" that gives table 3's banding                                   |
// | order     | sample i uses lattice point j = π(i mod n), π a keyed bijection (permute_index)|
// |           | keyed like the shift; it leaves each pair's point set unchanged but stops   |
// |           | pairs (and dimensions) from being copies of one another (pitfall 1)          |
// | 1D pairs  | pairs the named layout fills with two 1D quantities (pair_holds_1d_quantities)|
// |           | get per dimension (π_d(i) + 0.5)/n + shift_d mod 1                           |
// | blocks    | indices ≥ n start a new block i / n with its own shift and order             |
//
// The points of a pixel in a pair are a rank-1 set: p_j = shift + j·(1/φ, 1/n) mod 1, so any
// difference of two points is k·(1/φ, 1/n) mod 1 for an integer k. (It is a closed lattice only
// when n is a Fibonacci number F_m and 1/φ is replaced by F_{m−1}/F_m; eq. 19 uses 1/φ itself.)
#pragma once

#include "sampling/sampler.h"

namespace stratum {

// Point j of the unshifted n-point lattice of eq. 19, in double.
struct LatticePoint {
    double x = 0, y = 0;
};
LatticePoint fibonacci_lattice_point(uint32_t j, uint32_t n);

class FibonacciSampler : public Sampler {
public:
    explicit FibonacciSampler(const SamplerSettings& settings, bool per_pixel_shift = true)
        : spp_(settings.samples > 0 ? settings.samples : 1),
          seed_(settings.seed),
          per_pixel_(per_pixel_shift) {}

    float get_1d(const PixelSample& s, uint32_t dimension) const override;
    Vec2 get_2d(const PixelSample& s, uint32_t dimension) const override;

    // The toroidal shift of the pair starting at even `dimension` for the block of sample s.
    LatticePoint shift(const PixelSample& s, uint32_t dimension) const;

private:
    uint64_t key(const PixelSample& s, uint32_t dimension, uint32_t tag) const;
    uint32_t spp_, seed_;
    bool per_pixel_;
};

class StaticFibonacciSampler final : public FibonacciSampler {
public:
    explicit StaticFibonacciSampler(const SamplerSettings& settings) : FibonacciSampler(settings, false) {}
};

}  // namespace stratum
