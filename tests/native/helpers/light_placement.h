// Placing lights in the light tests: random points and directions (std::mt19937: a fixed seed
// gives the same draws on every platform the standard library runs on), and the transform of a
// light at a position facing along an axis.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>

#include "core/math.h"

namespace stratum_test {

struct Random {
    std::mt19937 engine;
    explicit Random(uint32_t seed) : engine(seed) {}
    float uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(engine); }
    // Uniform in the cube [-extent, extent]³.
    stratum::Vec3 point(float extent) {
        return {uniform(-extent, extent), uniform(-extent, extent), uniform(-extent, extent)};
    }
    // Uniform on the unit sphere (z uniform in [-1, 1], Archimedes).
    stratum::Vec3 direction() {
        const float z = uniform(-1.0f, 1.0f), phi = uniform(0.0f, 2.0f * stratum::kPi);
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        return {r * std::cos(phi), r * std::sin(phi), z};
    }
};

// A light's transform: at `position`, its local −Z (the direction area and spot lights face)
// along `axis`, scaled by `scale` in its plane.
inline stratum::Transform facing(stratum::Vec3 position, stratum::Vec3 axis, float scale = 1.0f) {
    const stratum::Frame frame = stratum::Frame::from_normal(-axis);
    const stratum::Vec3 x = frame.s * scale, y = frame.t * scale, z = frame.n;
    const float m[12] = {x.x, y.x, z.x, position.x, x.y, y.y, z.y, position.y, x.z, y.z, z.z, position.z};
    return stratum::Transform::from_row_major(m);
}

}  // namespace stratum_test
