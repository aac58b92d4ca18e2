// Vector arithmetic, distance metrics and cell hashing of Cycles' Voronoi texture
// (kernel/svm/voronoi.h at v3.4.0 and v5.0.0), for N = 1..4 dimensions, with Cycles' float
// operations in Cycles' order so that results agree to the last bit where the compilers allow:
//
// * a float2 or float4 divided by a scalar is multiplied by its reciprocal, a float3 is divided
//   (util/math_float{2,3,4}.h); a float4 dot product and component sum add pairwise,
//   (x + y) + (z + w), as SSE's dpps and hadd do; a float3's add left to right.
// * Blender 3.4's 4D Manhattan and Minkowski distances add left to right (scalar code), 4.x's
//   pairwise (reduce_add); the Euclidean distance is sqrt(dot) in both.
// * Cells are hashed by their float coordinates with lookup3 (cycles_hash.h) up to 4.5, and by
//   their integer coordinates with PCG (cycles_pcg_hash.h) from 5.0 on, except in 1D.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "shading/cycles_hash.h"
#include "shading/cycles_pcg_hash.h"

namespace stratum::voronoi {

// Which Blender's Voronoi: the node's mode 3.
enum Generation : int32_t {
    Blender3,   // 2.81-3.6: one octave; searches start at distance 8
    Blender40,  // 4.0-4.4: fractal; searches start at FLT_MAX; smooth F1 seeded by the first cell
    Blender45,  // 4.5: F1 and the n-sphere radius compare squared (bound) distances
    Blender50,  // 5.0+: as 4.5, cells hashed by integer coordinates (PCG)
    GenerationCount
};
enum Metric : int32_t { Euclidean, Manhattan, Chebychev, Minkowski, MetricCount };

// N floats; a struct (not an alias of std::array) so that its operators are found and deduced.
template <int N>
struct Vec {
    std::array<float, N> c{};
    float& operator[](int i) { return c[i]; }
    float operator[](int i) const { return c[i]; }
    void fill(float f) { c.fill(f); }
};

template <int N>
Vec<N> operator+(const Vec<N>& a, const Vec<N>& b) {
    Vec<N> r;
    for (int i = 0; i < N; ++i) r[i] = a[i] + b[i];
    return r;
}
template <int N>
Vec<N> operator-(const Vec<N>& a, const Vec<N>& b) {
    Vec<N> r;
    for (int i = 0; i < N; ++i) r[i] = a[i] - b[i];
    return r;
}
template <int N>
Vec<N> operator*(const Vec<N>& a, float f) {
    Vec<N> r;
    for (int i = 0; i < N; ++i) r[i] = a[i] * f;
    return r;
}
template <int N>
Vec<N> floor(const Vec<N>& a) {
    Vec<N> r;
    for (int i = 0; i < N; ++i) r[i] = std::floor(a[i]);
    return r;
}
// Cycles' mix(a, b, t) = a + t * (b - a).
inline float mix(float a, float b, float t) { return a + t * (b - a); }
template <int N>
Vec<N> mix(const Vec<N>& a, const Vec<N>& b, float t) {
    Vec<N> r;
    for (int i = 0; i < N; ++i) r[i] = mix(a[i], b[i], t);
    return r;
}
// a / f as Cycles' floatN operator/ computes it (see the top).
template <int N>
Vec<N> divide(const Vec<N>& a, float f) {
    if constexpr (N == 3 || N == 1) {
        Vec<N> r;
        for (int i = 0; i < N; ++i) r[i] = a[i] / f;
        return r;
    } else {
        return a * (1.0f / f);
    }
}
// Sum of components in Cycles' order.
template <int N>
float sum(const Vec<N>& a, bool pairwise4) {
    if constexpr (N == 4) {
        if (pairwise4) return (a[0] + a[1]) + (a[2] + a[3]);
    }
    float s = a[0];
    for (int i = 1; i < N; ++i) s += a[i];
    return s;
}
template <int N>
float dot(const Vec<N>& a, const Vec<N>& b) {
    Vec<N> p;
    for (int i = 0; i < N; ++i) p[i] = a[i] * b[i];
    return sum<N>(p, true);
}
template <int N>
float length(const Vec<N>& a) {
    if constexpr (N == 1) return std::fabs(a[0]);
    return std::sqrt(dot<N>(a, a));
}
template <int N>
Vec<N> normalize(const Vec<N>& a) {
    return divide<N>(a, length<N>(a));
}
// Cycles' min/max/clamp: NaN takes the bound (clamp(NaN, lo, hi) = lo).
inline float cmin(float a, float b) { return a < b ? a : b; }
inline float cmax(float a, float b) { return a > b ? a : b; }
inline float clamp(float a, float lo, float hi) { return cmin(cmax(a, lo), hi); }
inline float smoothstep(float edge0, float edge1, float x) {
    if (x < edge0) return 0.0f;
    if (x >= edge1) return 1.0f;
    const float t = (x - edge0) / (edge1 - edge0);
    return (3.0f - 2.0f * t) * (t * t);
}

struct MetricParams {
    Metric metric = Euclidean;
    float exponent = 1.0f;
    Generation generation = Blender3;
};

// voronoi_distance(a, b): |a - b| in 1D whatever the metric; else the metric's distance.
template <int N>
float distance(const Vec<N>& a, const Vec<N>& b, const MetricParams& p) {
    const Vec<N> d = a - b;
    if constexpr (N == 1) {
        return std::fabs(d[0]);
    } else {
        Vec<N> m;
        const bool pairwise = p.generation != Blender3;
        switch (p.metric) {
            case Euclidean:
                return length<N>(d);
            case Manhattan:
                for (int i = 0; i < N; ++i) m[i] = std::fabs(d[i]);
                return sum<N>(m, pairwise);
            case Chebychev: {
                float r = std::fabs(d[0]);
                for (int i = 1; i < N; ++i) r = cmax(r, std::fabs(d[i]));
                return r;
            }
            case Minkowski:
                for (int i = 0; i < N; ++i) m[i] = std::pow(std::fabs(d[i]), p.exponent);
                return std::pow(sum<N>(m, pairwise), 1.0f / p.exponent);
            default:
                return 0.0f;
        }
    }
}

// voronoi_distance_bound (4.5+): a cheaper quantity ordered as the distance (squared
// Euclidean, Minkowski without the root).
template <int N>
float distance_bound(const Vec<N>& a, const Vec<N>& b, const MetricParams& p) {
    const Vec<N> d = a - b;
    if (p.metric == Euclidean) return dot<N>(d, d);
    if (p.metric == Minkowski) {
        Vec<N> m;
        for (int i = 0; i < N; ++i) m[i] = std::pow(std::fabs(d[i]), p.exponent);
        return sum<N>(m, true);
    }
    return distance<N>(a, b, p);
}

// A cell of the lattice: its float coordinates and (5.0's hash) their integer values.
template <int N>
struct Cell {
    Vec<N> position;
    std::array<int32_t, N> index;
    bool integer_hash;  // PCG on integer coordinates (5.0, N >= 2), else lookup3 on floats

    Cell(const Vec<N>& p, Generation g) : position(p), index{}, integer_hash(g == Blender50 && N >= 2) {
        for (int i = 0; i < N; ++i) index[i] = cycles_pcg::to_int(p[i]);
    }
};

// The jitter of the feature point of the cell at `offset` from `cell`, in [0, 1]^N.
template <int N>
Vec<N> cell_jitter(const Cell<N>& cell, const std::array<int32_t, N>& offset) {
    namespace h = cycles_hash;
    if (cell.integer_hash) {
        std::array<int32_t, N> k;
        for (int i = 0; i < N; ++i) k[i] = cycles_pcg::add(cell.index[i], offset[i]);
        Vec<N> r{};
        if constexpr (N == 2) {
            const auto v = cycles_pcg::pcg2(k[0], k[1]);
            for (int i = 0; i < 2; ++i) r[i] = cycles_pcg::to_unit(v[i]);
        } else if constexpr (N == 3) {
            const auto v = cycles_pcg::pcg3(k[0], k[1], k[2]);
            for (int i = 0; i < 3; ++i) r[i] = cycles_pcg::to_unit(v[i]);
        } else if constexpr (N == 4) {
            const auto v = cycles_pcg::pcg4(k[0], k[1], k[2], k[3]);
            for (int i = 0; i < 4; ++i) r[i] = cycles_pcg::to_unit(v[i]);
        }
        return r;
    }
    Vec<N> c;
    for (int i = 0; i < N; ++i) c[i] = cell.position[i] + static_cast<float>(offset[i]);
    if constexpr (N == 1) {
        return {h::hash_float(c[0])};
    } else if constexpr (N == 2) {
        const auto v = h::hash_float2_to_float2(c[0], c[1]);
        return {v.x, v.y};
    } else if constexpr (N == 3) {
        const auto v = h::hash_float3_to_float3(c[0], c[1], c[2]);
        return {v.x, v.y, v.z};
    } else {
        const auto v = h::hash_float4_to_float4(c[0], c[1], c[2], c[3]);
        return {v.x, v.y, v.z, v.w};
    }
}

// The colour of the cell at `offset` from `cell`.
template <int N>
Vec<3> cell_color(const Cell<N>& cell, const std::array<int32_t, N>& offset) {
    namespace h = cycles_hash;
    if (cell.integer_hash) {
        std::array<int32_t, 4> k{};
        for (int i = 0; i < N; ++i) k[i] = cycles_pcg::add(cell.index[i], offset[i]);
        Vec<3> r{};
        if constexpr (N == 4) {
            const auto v = cycles_pcg::pcg4(k[0], k[1], k[2], k[3]);
            for (int i = 0; i < 3; ++i) r[i] = cycles_pcg::to_unit(v[i]);
        } else {
            // 2D hashes (x, y, 0) in 3D.
            const auto v = cycles_pcg::pcg3(k[0], k[1], k[2]);
            for (int i = 0; i < 3; ++i) r[i] = cycles_pcg::to_unit(v[i]);
        }
        return r;
    }
    Vec<N> c;
    for (int i = 0; i < N; ++i) c[i] = cell.position[i] + static_cast<float>(offset[i]);
    h::Hash3 v{};
    if constexpr (N == 1) v = h::hash_float_to_float3(c[0]);
    if constexpr (N == 2) v = h::hash_float2_to_float3(c[0], c[1]);
    if constexpr (N == 3) v = h::hash_float3_to_float3(c[0], c[1], c[2]);
    if constexpr (N == 4) v = h::hash_float4_to_float3(c[0], c[1], c[2], c[3]);
    return {v.x, v.y, v.z};
}

// Calls f(offset) for every offset in [-r, r]^N, x fastest (Cycles' loop nesting).
template <int N, typename F>
void for_each_offset(int r, F&& f) {
    std::array<int32_t, N> o;
    o.fill(-r);
    for (;;) {
        f(o);
        int i = 0;
        while (i < N && o[i] == r) o[i++] = -r;
        if (i == N) return;
        ++o[i];
    }
}

template <int N>
Vec<N> to_float(const std::array<int32_t, N>& o) {
    Vec<N> r;
    for (int i = 0; i < N; ++i) r[i] = static_cast<float>(o[i]);
    return r;
}

}  // namespace stratum::voronoi
