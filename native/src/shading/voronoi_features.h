// One octave of Cycles' Voronoi texture (kernel/svm/voronoi.h, v3.4.0 and v5.0.0): the features
// F1, F2, smooth F1, distance to edge and n-sphere radius of the cells around a point, in N = 1..4
// dimensions. Worley's cellular texture: one feature point per unit cell, jittered by the cell's
// hash times the randomness; smooth F1 is Inigo Quilez's smooth minimum over a 5^N window, the
// distance to edge his two-pass search over 3^N cells. Used by nodes/voronoi_texture.cpp.
#pragma once

#include <cfloat>

#include "shading/cycles_hash_lanes.h"
#include "shading/voronoi_math.h"

namespace stratum::voronoi {

struct Params {
    MetricParams metric;
    float randomness = 1.0f;  // clamped to [0, 1]
    float smoothness = 0.0f;  // half the socket's, clamped to [0, 0.5]
};

template <int N>
struct Octave {
    float distance = 0.0f;
    Vec<3> color{};
    Vec<N> position{};  // in the scaled coordinates
};

// The distance a search starts from: 8 in 3.x, FLT_MAX from 4.0 on.
inline float start_distance(const Params& p) { return p.metric.generation == Blender3 ? 8.0f : FLT_MAX; }

template <int N>
Vec<N> feature_point(const Cell<N>& cell, const std::array<int32_t, N>& o, float randomness) {
    return to_float<N>(o) + cell_jitter<N>(cell, o) * randomness;
}

// The feature points of the 3^N cells around `cell` (offsets in [-1, 1]^N), in for_each_offset's
// order: each search over them reads this table instead of hashing a cell again. In 3D with
// lookup3 (Blender 3.x-4.5) the 27 cells are hashed together (cycles_hash_lanes.h), to the same
// bits as cell_jitter's.
template <int N>
inline constexpr int kNeighbours = N == 1   ? 3
                                   : N == 2 ? 9
                                   : N == 3 ? 27
                                            : 81;

// The offset of the k-th of those cells.
template <int N>
std::array<int32_t, N> neighbour_offset(int k) {
    std::array<int32_t, N> o;
    for (int i = 0; i < N; ++i, k /= 3) o[i] = k % 3 - 1;
    return o;
}

template <int N>
std::array<Vec<N>, kNeighbours<N>> neighbour_points(const Cell<N>& cell, float randomness) {
    std::array<Vec<N>, kNeighbours<N>> points;
    if constexpr (N == 3) {
        if (!cell.integer_hash) {
            constexpr int kCount = kNeighbours<3>;
            uint32_t kx[kCount], ky[kCount], kz[kCount], hx[kCount], hy[kCount], hz[kCount];
            // Plain loops over the offsets (x fastest): for_each_offset's array, written a lane at
            // a time and read whole, stalls the store forwarding here.
            float ox[kCount], oy[kCount], oz[kCount];
            for (int k = 0; k < kCount; ++k) {
                ox[k] = static_cast<float>(k % 3 - 1);
                oy[k] = static_cast<float>(k / 3 % 3 - 1);
                oz[k] = static_cast<float>(k / 9 - 1);
                kx[k] = cycles_hash::bits(cell.position[0] + ox[k]);
                ky[k] = cycles_hash::bits(cell.position[1] + oy[k]);
                kz[k] = cycles_hash::bits(cell.position[2] + oz[k]);
            }
            // hash_float3_to_float3: (hash(x, y, z), hash(x, y, z, 1), hash(x, y, z, 2)).
            cycles_hash::hash_uint3_lanes<kCount>(kx, ky, kz, hx);
            cycles_hash::hash_uint4_lanes<kCount>(kx, ky, kz, cycles_hash::bits(1.0f), hy);
            cycles_hash::hash_uint4_lanes<kCount>(kx, ky, kz, cycles_hash::bits(2.0f), hz);
            // to_float(o) + jitter * randomness, as feature_point.
            for (int k = 0; k < kCount; ++k) {
                points[k][0] = ox[k] + cycles_hash::to_unit(hx[k]) * randomness;
                points[k][1] = oy[k] + cycles_hash::to_unit(hy[k]) * randomness;
                points[k][2] = oz[k] + cycles_hash::to_unit(hz[k]) * randomness;
            }
            return points;
        }
    }
    int k = 0;
    for_each_offset<N>(
        1, [&](const std::array<int32_t, N>& o) { points[k++] = feature_point<N>(cell, o, randomness); });
    return points;
}

template <int N>
Octave<N> f1(const Vec<N>& coord, const Params& p) {
    const Vec<N> cell_position = floor<N>(coord);
    const Vec<N> local = coord - cell_position;
    const Cell<N> cell(cell_position, p.metric.generation);
    const bool bound = N >= 2 && p.metric.generation >= Blender45;
    float best = start_distance(p);
    // The nearest cell by its index in the table; none (all distances NaN): offset 0, point 0.
    int target = -1;
    const auto points = neighbour_points<N>(cell, p.randomness);
    for (int k = 0; k < kNeighbours<N>; ++k) {
        const float d =
            bound ? distance_bound<N>(points[k], local, p.metric) : distance<N>(points[k], local, p.metric);
        if (d < best) {
            target = k;
            best = d;
        }
    }
    const Vec<N> target_point = target < 0 ? Vec<N>{} : points[target];
    Octave<N> out;
    out.distance = bound ? distance<N>(target_point, local, p.metric) : best;
    out.color = cell_color<N>(cell, target < 0 ? std::array<int32_t, N>{} : neighbour_offset<N>(target));
    out.position = target_point + cell_position;
    return out;
}

template <int N>
Octave<N> smooth_f1(const Vec<N>& coord, const Params& p) {
    const Vec<N> cell_position = floor<N>(coord);
    const Vec<N> local = coord - cell_position;
    const Cell<N> cell(cell_position, p.metric.generation);
    const bool seeded = p.metric.generation != Blender3;  // 4.x: the first cell's weight is 1
    const float s = p.smoothness;
    float smooth_distance = seeded ? 0.0f : 8.0f;
    Vec<3> smooth_color{};
    Vec<N> smooth_position{};
    float h = -1.0f;
    for_each_offset<N>(2, [&](const std::array<int32_t, N>& o) {
        const Vec<N> point = feature_point<N>(cell, o, p.randomness);
        const float d = distance<N>(point, local, p.metric);
        if (seeded && h == -1.0f)
            h = 1.0f;
        else
            h = smoothstep(0.0f, 1.0f, 0.5f + 0.5f * (smooth_distance - d) / s);
        float correction = s * h * (1.0f - h);
        smooth_distance = mix(smooth_distance, d, h) - correction;
        correction /= 1.0f + 3.0f * s;
        const Vec<3> color = cell_color<N>(cell, o);
        for (int i = 0; i < 3; ++i) smooth_color[i] = mix(smooth_color[i], color[i], h) - correction;
        for (int i = 0; i < N; ++i) smooth_position[i] = mix(smooth_position[i], point[i], h) - correction;
    });
    Octave<N> out;
    out.distance = smooth_distance;
    out.color = smooth_color;
    out.position = cell_position + smooth_position;
    return out;
}

template <int N>
Octave<N> f2(const Vec<N>& coord, const Params& p) {
    const Vec<N> cell_position = floor<N>(coord);
    const Vec<N> local = coord - cell_position;
    const Cell<N> cell(cell_position, p.metric.generation);
    float d1 = start_distance(p), d2 = d1;
    std::array<int32_t, N> offset1{}, offset2{};
    Vec<N> point1{}, point2{};
    const auto points = neighbour_points<N>(cell, p.randomness);
    int k = 0;
    for_each_offset<N>(1, [&](const std::array<int32_t, N>& o) {
        const Vec<N>& point = points[k++];
        const float d = distance<N>(point, local, p.metric);
        if (d < d1) {
            d2 = d1, offset2 = offset1, point2 = point1;
            d1 = d, offset1 = o, point1 = point;
        } else if (d < d2) {
            d2 = d, offset2 = o, point2 = point;
        }
    });
    Octave<N> out;
    out.distance = d2;
    out.color = cell_color<N>(cell, offset2);
    out.position = point2 + cell_position;
    return out;
}

template <int N>
float distance_to_edge(const Vec<N>& coord, const Params& p) {
    const Vec<N> cell_position = floor<N>(coord);
    const Vec<N> local = coord - cell_position;
    const Cell<N> cell(cell_position, p.metric.generation);
    if constexpr (N == 1) {
        // The edges are the midpoints between this cell's point and its neighbours'.
        const float mid = feature_point<1>(cell, {0}, p.randomness)[0];
        const float left = feature_point<1>(cell, {-1}, p.randomness)[0];
        const float right = feature_point<1>(cell, {1}, p.randomness)[0];
        return cmin(std::fabs((mid + left) / 2.0f - local[0]), std::fabs((mid + right) / 2.0f - local[0]));
    } else {
        Vec<N> to_closest{};
        float best = start_distance(p);
        const auto points = neighbour_points<N>(cell, p.randomness);
        for (const Vec<N>& point : points) {
            const Vec<N> to_point = point - local;
            const float d = dot<N>(to_point, to_point);
            if (d < best) {
                best = d;
                to_closest = to_point;
            }
        }
        best = start_distance(p);
        for (const Vec<N>& point : points) {
            const Vec<N> to_point = point - local;
            const Vec<N> across = to_point - to_closest;
            if (dot<N>(across, across) > 0.0001f) {
                // Distance from the point to the bisector of the two feature points.
                const float d = dot<N>(divide<N>(to_closest + to_point, 2.0f), normalize<N>(across));
                best = cmin(best, d);
            }
        }
        return best;
    }
}

// Half the (Euclidean) distance from the nearest feature point to its own nearest neighbour.
template <int N>
float n_sphere_radius(const Vec<N>& coord, const Params& p) {
    const Vec<N> cell_position = floor<N>(coord);
    const Vec<N> local = coord - cell_position;
    const Cell<N> cell(cell_position, p.metric.generation);
    // 4.5+ compares squared lengths (1D: absolute values in every version).
    const bool squared = N >= 2 && p.metric.generation >= Blender45;
    const auto measure = [&](const Vec<N>& v) { return squared ? dot<N>(v, v) : length<N>(v); };
    Vec<N> closest{};
    std::array<int32_t, N> closest_offset{};
    float best = start_distance(p);
    for_each_offset<N>(1, [&](const std::array<int32_t, N>& o) {
        const Vec<N> point = feature_point<N>(cell, o, p.randomness);
        const float d = measure(point - local);
        if (d < best) {
            best = d;
            closest = point;
            closest_offset = o;
        }
    });
    best = start_distance(p);
    Vec<N> neighbour{};
    for_each_offset<N>(1, [&](const std::array<int32_t, N>& o) {
        bool centre = true;
        for (int i = 0; i < N; ++i) centre = centre && o[i] == 0;
        if (centre) return;
        std::array<int32_t, N> at;
        for (int i = 0; i < N; ++i) at[i] = cycles_pcg::add(o[i], closest_offset[i]);
        const Vec<N> point = feature_point<N>(cell, at, p.randomness);
        const float d = measure(closest - point);
        if (d < best) {
            best = d;
            neighbour = point;
        }
    });
    return length<N>(neighbour - closest) / 2.0f;
}

}  // namespace stratum::voronoi
