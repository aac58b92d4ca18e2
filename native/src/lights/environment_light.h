// Blender World -> Background <- Environment Texture (equirectangular), importance-sampled.
//
// | parameter | meaning |
// |-----------|---------|
// | image     | width x height linear RGB radiance, rows top (up, +Z) to bottom, × strength |
// | rotation  | world-to-environment rotation R: the image is looked up at R·dir |
//
// Mapping (Cycles' direction_to_equirectangular, kernel/geom: range (−2π, π, −π, π)):
//     u = 0.5 − atan2(d.y, d.x)/(2π),   v = 1 − acos(d.z)/π   (v = 1 straight up)
// so the image centre column faces +X and its left edge −X, going through −Y at u = 0.25.
// Texel (i, j) (column i, row j from the top) covers u ∈ [i/W, (i+1)/W), v ∈ (1 − (j+1)/H, 1 − j/H].
// Lookup is nearest-texel (Cycles' "Closest" interpolation; Cycles' default "Linear" differs
// only within a texel).
//
// Sampling (textbook §4.7.3, pbrt's piecewise-constant 2D distribution): texel (i, j) is chosen
// with probability ∝ luminance(i, j) · sin θ_j (θ_j at the row centre), then (u, v) uniformly in
// it, so p(u, v) is piecewise constant with ∫ p du dv = 1; since dω = 2π² sin θ du dv, the
// solid-angle pdf is p(u, v) / (2π² sin θ). An all-black image is sampled by sin θ alone.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/math.h"
#include "lights/light.h"

namespace stratum {

class EnvironmentLight final : public Light {
public:
    // rgb: width*height*3 floats, already multiplied by the strength; rotation: row-major 3x3.
    EnvironmentLight(std::vector<float> rgb, uint32_t width, uint32_t height,
                     const std::array<float, 9>& rotation);

    bool is_delta() const override { return false; }
    // Rays that leave the scene find it (RenderScene::background), not LightSet::lamp_radiance.
    bool is_hittable_lamp() const override { return false; }
    // The flux of a uniform sky of the average radiance L̄ (solid-angle weighted) through the
    // scene's cross-section: π R² L̄.
    double power(float scene_radius) const override {
        return mean(average_) * kPi * scene_radius * scene_radius;
    }
    Rgb radiance(Vec3 world_dir) const;
    // A direction by the image's distribution; p and n play no part.
    bool sample(Vec3 p, Vec3 n, Vec2 u, TriangleSampling triangle_sampling, LightSample* out) const override;
    // Solid-angle pdf with which sample() returns world_dir.
    float pdf(Vec3 world_dir) const;
    // A light-tracing particle: the direction toward the sky ω by sample() (p_ω), then a
    // parallel beam along −ω over the disk of radius R perpendicular to ω and tangent to the
    // scene's bounding sphere (center, R) on the sky's side, point uniform (p_A = 1/(πR²)):
    // weight L(ω) πR² / p_ω (every ray from the sky that meets the scene crosses the disk).
    bool sample_emission(Vec2 u_position, Vec2 u_direction, Vec3 center, float radius,
                         EmissionSample* out) const override;

private:
    bool sample_direction(Vec2 u, LightSample* out) const;
    struct Texel {
        uint32_t i, j;
        float u, v, sin_theta;
    };
    Texel texel(Vec3 world_dir) const;
    Rgb at(uint32_t i, uint32_t j) const {
        const size_t k = 3 * (static_cast<size_t>(j) * width_ + i);
        return {rgb_[k], rgb_[k + 1], rgb_[k + 2]};
    }

    std::vector<float> rgb_;
    uint32_t width_, height_;
    std::array<float, 9> rotation_;  // world to environment
    std::vector<float> row_cdf_;     // height_ + 1 entries, row_cdf_[0] = 0, last = 1
    std::vector<float> column_cdf_;  // per row, width_ + 1 entries
    std::vector<float> density_;     // p(u, v) of each texel
    Rgb average_;
};

}  // namespace stratum
