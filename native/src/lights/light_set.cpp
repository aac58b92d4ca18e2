#include "lights/light_set.h"

#include <algorithm>
#include <unordered_map>

namespace stratum {

uint32_t LightSet::add(Light light, uint32_t object, uint32_t visibility) {
    if (std::holds_alternative<EnvironmentLight>(light)) environment_ = lights_.size();
    // Lamps with an emitting surface that rays can meet: area lamps, and point/spot lamps with a
    // radius (their disk facing the ray's origin); a zero radius is a delta light no ray finds.
    const bool hittable = std::visit(
        [](const auto& l) {
            using T = std::decay_t<decltype(l)>;
            if constexpr (std::is_same_v<T, AreaLight>) {
                return true;
            } else if constexpr (std::is_same_v<T, PointLight> || std::is_same_v<T, SpotLight>) {
                return l.radius() > 0.0f;
            } else {
                return false;
            }
        },
        light);
    if (hittable) hittable_lamps_.push_back(static_cast<uint32_t>(lights_.size()));
    lights_.push_back(std::move(light));
    object_.push_back(object);
    visibility_.push_back(visibility);
    return static_cast<uint32_t>(lights_.size() - 1);
}

void LightSet::finalize(float scene_radius) {
    std::vector<double> power(lights_.size());
    for (size_t i = 0; i < lights_.size(); ++i) {
        power[i] = std::visit(
            [&](const auto& l) -> double {
                using T = std::decay_t<decltype(l)>;
                // The sun's flux through the scene's cross-section; the environment's likewise,
                // from its average radiance (π·R²·L̄, the flux of a uniform sky through a disk).
                if constexpr (std::is_same_v<T, SunLight>) {
                    return l.irradiance().average() * kPi * scene_radius * scene_radius;
                } else if constexpr (std::is_same_v<T, EnvironmentLight>) {
                    return l.average().average() * kPi * scene_radius * scene_radius;
                } else {
                    return l.power();
                }
            },
            lights_[i]);
    }
    double total = 0.0;
    std::unordered_map<uint32_t, double> object_power;
    for (size_t i = 0; i < lights_.size(); ++i) {
        total += power[i];
        object_power[object_[i]] += power[i];
    }
    std::unordered_map<uint32_t, size_t> object_size;
    for (uint32_t o : object_) ++object_size[o];
    const double objects = static_cast<double>(object_power.size());
    probability_.resize(lights_.size());
    cdf_.resize(lights_.size());
    double running = 0.0;
    for (size_t i = 0; i < lights_.size(); ++i) {
        // Zero total (or object) power: that half of the mixture is uniform instead.
        const double by_power = total > 0.0 ? power[i] / total : 1.0 / static_cast<double>(lights_.size());
        const double in_object = object_power[object_[i]] > 0.0
                                     ? power[i] / object_power[object_[i]]
                                     : 1.0 / static_cast<double>(object_size[object_[i]]);
        const double p = 0.5 * by_power + 0.5 * in_object / objects;
        probability_[i] = static_cast<float>(p);
        running += p;
        cdf_[i] = static_cast<float>(running);
    }
    if (!cdf_.empty()) cdf_.back() = 1.0f;
}

bool LightSet::sample(Vec3 p, float u_choice, Vec2 u, LightSample* out) const {
    if (lights_.empty()) return false;
    const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u_choice);
    const size_t index = std::min(static_cast<size_t>(it - cdf_.begin()), lights_.size() - 1);
    const float choice = probability_[index];
    if (!(choice > 0.0f)) return false;
    const bool ok = std::visit(
        [&](const auto& l) {
            using T = std::decay_t<decltype(l)>;
            if constexpr (std::is_same_v<T, SunLight> || std::is_same_v<T, EnvironmentLight>) {
                return l.sample(u, out);
            } else {
                return l.sample(p, u, out);
            }
        },
        lights_[index]);
    if (!ok) return false;
    out->pdf *= choice;
    out->visibility = visibility_[index];
    return true;
}

float LightSet::emissive_triangle_pdf(uint32_t index, Vec3 p, Vec3 hit) const {
    const auto& tri = std::get<EmissiveTriangle>(lights_[index]);
    return probability_[index] * tri.pdf(p, hit);
}

Rgb LightSet::lamp_radiance(Vec3 origin, Vec3 dir, float t_max, uint32_t visibility, float* pdf,
                            float* t_out) const {
    Rgb radiance(0.0f);
    float nearest = t_max, nearest_pdf = 0.0f;
    for (const uint32_t i : hittable_lamps_) {
        if (!(visibility_[i] & visibility)) continue;
        float t, solid_angle_pdf;
        Rgb L;
        const bool hit = std::visit(
            [&](const auto& l) {
                using T = std::decay_t<decltype(l)>;
                if constexpr (std::is_same_v<T, AreaLight> || std::is_same_v<T, PointLight> ||
                              std::is_same_v<T, SpotLight>) {
                    return l.intersect(origin, dir, nearest, &t, &L, &solid_angle_pdf);
                } else {
                    return false;
                }
            },
            lights_[i]);
        if (hit) {
            nearest = t;
            radiance = L;
            nearest_pdf = probability_[i] * solid_angle_pdf;
        }
    }
    if (pdf) *pdf = nearest_pdf;
    if (t_out) *t_out = nearest;
    return radiance;
}

const EnvironmentLight* LightSet::environment() const {
    return environment_ == SIZE_MAX ? nullptr : &std::get<EnvironmentLight>(lights_[environment_]);
}

float LightSet::environment_pdf(Vec3 wi) const {
    if (environment_ == SIZE_MAX) return 0.0f;
    return probability_[environment_] * std::get<EnvironmentLight>(lights_[environment_]).pdf(wi);
}

}  // namespace stratum
