// The hemisphere distributions of seed 000 (table: uniform in angles, sine = uniform in solid
// angle, sine-cosine = cosine-weighted), selectable for diffuse scattering and ambient
// occlusion. Each is used with its exact solid-angle pdf, so every choice is unbiased and only
// the variance differs.
//
// | name           | joint pdf p(φ,θ) | solid-angle pdf   | warp (warps.h)                    |
// |----------------|------------------|-------------------|-----------------------------------|
// | uniform_angles | 1/π²             | 1/(π² sin θ)      | sample_uniform_angles_hemisphere  |
// | uniform        | sin θ/(2π)       | 1/(2π)            | sample_uniform_hemisphere         |
// | cosine         | sin θ cos θ/π    | cos θ/π           | sample_cosine_hemisphere          |
#pragma once

#include <span>
#include <string_view>

#include "core/math.h"
#include "core/registry.h"
#include "sampling/warps.h"

namespace stratum {

enum class HemisphereDistribution { UniformAngles, Uniform, Cosine };

std::span<const RegistryEntry> hemisphere_registry();
// False when `name` is not a distribution.
bool parse_hemisphere(std::string_view name, HemisphereDistribution* out);

// Direction in the local frame (z = normal), z >= 0.
inline Vec3 sample_hemisphere(HemisphereDistribution d, Vec2 u) {
    switch (d) {
        case HemisphereDistribution::UniformAngles:
            return sample_uniform_angles_hemisphere(u);
        case HemisphereDistribution::Uniform:
            return sample_uniform_hemisphere(u);
        case HemisphereDistribution::Cosine:
            break;
    }
    return sample_cosine_hemisphere(u);
}

// Solid-angle density of sample_hemisphere(d, ·) at a direction with cos θ = cos_theta.
inline float hemisphere_pdf(HemisphereDistribution d, float cos_theta) {
    if (cos_theta < 0.0f) return 0.0f;
    switch (d) {
        case HemisphereDistribution::UniformAngles:
            return uniform_angles_hemisphere_pdf(cos_theta);
        case HemisphereDistribution::Uniform:
            return uniform_hemisphere_pdf();
        case HemisphereDistribution::Cosine:
            break;
    }
    return cosine_hemisphere_pdf(cos_theta);
}

}  // namespace stratum
