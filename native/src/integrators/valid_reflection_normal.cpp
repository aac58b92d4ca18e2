#include "integrators/valid_reflection_normal.h"

#include <algorithm>

namespace stratum {

Vec3 ensure_valid_reflection(Vec3 ng, Vec3 wo, Vec3 ns) {
    const float wo_z = dot(ng, wo);
    const float threshold = std::min(0.9f * wo_z, 0.01f);
    const Vec3 reflected = ns * (2.0f * dot(ns, wo)) - wo;
    if (dot(ng, reflected) >= threshold) return ns;

    const Vec3 tangent_part = ns - ng * dot(ns, ng);
    const float tangent_length = length(tangent_part);
    // ns == ng reflects wo to a direction at wo's own height, which passed the test above; this
    // guards only against a normal that is not unit length.
    if (!(tangent_length > 0.0f)) return ng;
    const Vec3 x_axis = tangent_part / tangent_length;
    const float wo_x = dot(wo, x_axis);
    const float a = wo_x * wo_x + wo_z * wo_z;
    const float b = safe_sqrt(wo_x * wo_x * (a - threshold * threshold));
    const float c = wo_z * threshold + a;
    const float z2_plus = 0.5f * (c + b) / a, z2_minus = 0.5f * (c - b) / a;
    // Tolerances as in Cycles: z^2 a little above 1 is rounding; z^2 near 0 would lay the
    // normal into the surface.
    constexpr float kEps = 1e-5f;
    const auto usable = [](float z2) { return z2 > kEps && z2 <= 1.0f + kEps; };
    const auto normal_of = [&](float z2) { return x_axis * safe_sqrt(1.0f - z2) + ng * safe_sqrt(z2); };
    // Height above the surface of wo reflected about the normal (sqrt(1 - z^2), 0, z).
    const auto reflected_height = [&](float z2) {
        const float z = safe_sqrt(z2);
        return 2.0f * (safe_sqrt(1.0f - z2) * wo_x + z * wo_z) * z - wo_z;
    };

    const bool plus_ok = usable(z2_plus), minus_ok = usable(z2_minus);
    if (plus_ok && minus_ok) {
        const float r_plus = reflected_height(z2_plus), r_minus = reflected_height(z2_minus);
        if (r_plus >= kEps && r_minus >= kEps) return normal_of(r_plus < r_minus ? z2_plus : z2_minus);
        return normal_of(r_plus > r_minus ? z2_plus : z2_minus);
    }
    if (plus_ok) return normal_of(z2_plus);
    if (minus_ok) return normal_of(z2_minus);
    return ng;
}

}  // namespace stratum
