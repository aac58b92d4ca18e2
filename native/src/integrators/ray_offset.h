// Where a secondary ray starts: the hit point moved off the surface along the geometric
// normal by a distance relative to the point's magnitude, so float rounding of the hit position
// cannot put the origin behind the surface it leaves.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace stratum {

// Shadow rays stop this fraction short of the light point so they do not hit the emitter.
inline constexpr float kShadowRayShortening = 1.0f - 1e-4f;

inline Vec3 offset_ray_origin(Vec3 p, Vec3 n) {
    const float scale = std::max({1.0f, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    return p + n * (1e-4f * scale);
}

}  // namespace stratum
