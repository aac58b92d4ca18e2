// The lane-wise forms the node evaluation runs for speed (cycles_hash_lanes.h, Perlin 3D's
// corners, Voronoi's table of 27 feature points) against the one-at-a-time formulas they
// replace, bit for bit: a faster evaluation must not change a single render.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include "shading/cycles_hash.h"
#include "shading/cycles_hash_lanes.h"
#include "shading/perlin_noise.h"
#include "shading/voronoi_features.h"

namespace {

using namespace stratum;
namespace hash = stratum::cycles_hash;

// A fixed sequence of floats in [-span, span], with a few magnitudes where float spacing is coarse.
struct Points {
    uint32_t state = 12345u;
    float next(float span) {
        state = state * 1664525u + 1013904223u;
        return (static_cast<float>(state >> 8) / 16777216.0f * 2.0f - 1.0f) * span;
    }
};

TEST(NodeLanes, HashLanesEqualTheScalarHashes) {
    constexpr int kLanes = 27;  // a remainder after the vector width, as Voronoi's
    uint32_t x[kLanes], y[kLanes], z[kLanes], h3[kLanes], h4[kLanes];
    uint32_t state = 7u;
    for (int round = 0; round < 200; ++round) {
        for (int i = 0; i < kLanes; ++i) {
            x[i] = state = state * 747796405u + 2891336453u;
            y[i] = state = state * 747796405u + 2891336453u;
            z[i] = state = state * 747796405u + 2891336453u;
        }
        const uint32_t w = state;
        hash::hash_uint3_lanes<kLanes>(x, y, z, h3);
        hash::hash_uint4_lanes<kLanes>(x, y, z, w, h4);
        for (int i = 0; i < kLanes; ++i) {
            ASSERT_EQ(h3[i], hash::hash_uint3(x[i], y[i], z[i])) << round << " " << i;
            ASSERT_EQ(h4[i], hash::hash_uint4(x[i], y[i], z[i], w)) << round << " " << i;
        }
    }
}

// Perlin 3D one corner at a time: OSL's gradient of the 12 cube edges with branches, the eight
// corners blended x, then y, then z (the order perlin_noise.cpp documents).
float grad3_branches(uint32_t hash, float x, float y, float z) {
    const uint32_t h = hash & 15u;
    const float u = h < 8 ? x : y;
    const float v = h < 4 ? y : ((h == 12 || h == 14) ? x : z);
    return ((h & 1u) ? -u : u) + ((h & 2u) ? -v : v);
}
float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

float perlin_3d_scalar(float x, float y, float z) {
    const float ix = std::floor(x), iy = std::floor(y), iz = std::floor(z);
    const auto lattice = [](float f) { return static_cast<uint32_t>(perlin::floor_to_lattice(f)); };
    const uint32_t X = lattice(ix), Y = lattice(iy), Z = lattice(iz);
    const float fx = x - ix, fy = y - iy, fz = z - iz;
    float v[8];
    for (uint32_t c = 0; c < 8; ++c) {
        const uint32_t dx = c & 1u, dy = (c >> 1) & 1u, dz = c >> 2;
        v[c] = grad3_branches(hash::hash_uint3(X + dx, Y + dy, Z + dz), fx - static_cast<float>(dx),
                              fy - static_cast<float>(dy), fz - static_cast<float>(dz));
    }
    const float u = fade(fx), t = fade(fy), s = fade(fz);
    const float u1 = 1.0f - u, t1 = 1.0f - t, s1 = 1.0f - s;
    return s1 * (t1 * (v[0] * u1 + v[1] * u) + t * (v[2] * u1 + v[3] * u)) +
           s * (t1 * (v[4] * u1 + v[5] * u) + t * (v[6] * u1 + v[7] * u));
}

TEST(NodeLanes, Perlin3dEqualsTheCornerByCornerFormula) {
    Points points;
    for (float span : {2.0f, 40.0f, 3.0e4f, 2.0e7f}) {
        for (int i = 0; i < 20000; ++i) {
            const float x = points.next(span), y = points.next(span), z = points.next(span);
            const float expected = perlin_3d_scalar(x, y, z), got = perlin::perlin_3d(x, y, z);
            ASSERT_EQ(std::bit_cast<uint32_t>(got), std::bit_cast<uint32_t>(expected))
                << x << " " << y << " " << z;
        }
    }
}

TEST(NodeLanes, VoronoiNeighbourTableEqualsEachCellsFeaturePoint) {
    Points points;
    for (int g = 0; g < voronoi::GenerationCount; ++g) {
        const auto generation = static_cast<voronoi::Generation>(g);
        for (int i = 0; i < 300; ++i) {
            const voronoi::Vec<3> at{{points.next(50.0f), points.next(50.0f), points.next(50.0f)}};
            const float randomness = i % 3 == 0 ? 1.0f : std::fabs(points.next(1.0f));
            const voronoi::Cell<3> cell(voronoi::floor<3>(at), generation);
            const auto table = voronoi::neighbour_points<3>(cell, randomness);
            int k = 0;
            voronoi::for_each_offset<3>(1, [&](const std::array<int32_t, 3>& o) {
                const voronoi::Vec<3> expected = voronoi::feature_point<3>(cell, o, randomness);
                for (int c = 0; c < 3; ++c) {
                    ASSERT_EQ(std::bit_cast<uint32_t>(table[k][c]), std::bit_cast<uint32_t>(expected[c]))
                        << "generation " << g << " cell " << k << " component " << c;
                }
                ++k;
            });
            ASSERT_EQ(k, 27);
        }
    }
}

}  // namespace
