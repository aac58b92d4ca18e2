// All lights of a scene and the discrete distribution that next-event estimation chooses them
// by: probability proportional to emitted power (textbook 5.14, p(j) = Φ_j / ΣΦ).
#pragma once

#include <cstdint>
#include <variant>
#include <vector>

#include "lights/area_light.h"
#include "lights/emissive_triangle.h"
#include "lights/point_light.h"
#include "lights/sun_light.h"

namespace stratum {

class LightSet {
public:
    using Light = std::variant<PointLight, SunLight, AreaLight, EmissiveTriangle>;

    // scene_radius: radius of a sphere bounding the scene, to give the sun a power.
    // Returns the index of the added light.
    uint32_t add(Light light);
    void finalize(float scene_radius);

    bool empty() const { return lights_.empty(); }
    size_t size() const { return lights_.size(); }
    // Chooses a light with u_choice and samples it with u; out->pdf includes the choice.
    bool sample(Vec3 p, float u_choice, Vec2 u, LightSample* out) const;
    // Pdf (choice × solid angle) with which sample() reaches `hit` on emissive triangle `index`.
    float emissive_triangle_pdf(uint32_t index, Vec3 p, Vec3 hit) const;

private:
    std::vector<Light> lights_;
    std::vector<float> cdf_;  // cdf_[i] = P(choice < i+1), last = 1
    std::vector<float> probability_;
};

}  // namespace stratum
