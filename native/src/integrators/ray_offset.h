// Where a secondary ray starts: the hit point moved off the surface along the geometric
// normal by a distance relative to the point's magnitude, so float rounding of the hit position
// cannot put the origin behind the surface it leaves.
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace stratum {

inline float offset_distance(Vec3 p) {
    return 1e-4f * std::max({1.0f, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
}

inline Vec3 offset_ray_origin(Vec3 p, Vec3 n) { return p + n * offset_distance(p); }

// A shadow ray from `origin` to a point on a light stops short of it by twice the offset a ray
// leaving that point would get, so it cannot hit the emitting surface itself.
struct ShadowRay {
    Vec3 direction;
    float t_max;
};
inline ShadowRay shadow_ray_to(Vec3 origin, Vec3 target) {
    const Vec3 d = target - origin;
    const float len = length(d);
    return {d / len, std::max(0.0f, len - 2.0f * offset_distance(target))};
}

}  // namespace stratum
