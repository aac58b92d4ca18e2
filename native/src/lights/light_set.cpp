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
    const bool delta = std::visit(
        [](const auto& l) {
            using T = std::decay_t<decltype(l)>;
            if constexpr (std::is_same_v<T, PointLight> || std::is_same_v<T, SpotLight>) {
                return l.radius() <= 0.0f;
            } else if constexpr (std::is_same_v<T, SunLight>) {
                return l.is_delta();
            } else {
                return false;
            }
        },
        light);
    if (delta) ++delta_lights_;
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
                    return mean(l.irradiance()) * kPi * scene_radius * scene_radius;
                } else if constexpr (std::is_same_v<T, EnvironmentLight>) {
                    return mean(l.average()) * kPi * scene_radius * scene_radius;
                } else {
                    return l.power();
                }
            },
            lights_[i]);
    }
    power_ = power;
    double total = 0.0;
    std::unordered_map<uint32_t, double> object_power;
    for (size_t i = 0; i < lights_.size(); ++i) {
        total += power[i];
        object_power[object_[i]] += power[i];
    }
    std::unordered_map<uint32_t, size_t> object_size;
    for (uint32_t o : object_) ++object_size[o];
    const double objects = static_cast<double>(object_power.size());
    const double uniform = 1.0 / static_cast<double>(std::max<size_t>(1, lights_.size()));
    for (uint32_t mode = 0; mode < kLightSelectionModes; ++mode) {
        probability_[mode].resize(lights_.size());
        cdf_[mode].resize(lights_.size());
        double running = 0.0;
        for (size_t i = 0; i < lights_.size(); ++i) {
            // Zero total (or object) power: the power-proportional part is uniform instead.
            const double by_power = total > 0.0 ? power[i] / total : uniform;
            double p = uniform;
            switch (static_cast<LightSelection>(mode)) {
                case LightSelection::Mixed: {
                    const double in_object = object_power[object_[i]] > 0.0
                                                 ? power[i] / object_power[object_[i]]
                                                 : 1.0 / static_cast<double>(object_size[object_[i]]);
                    p = 0.5 * by_power + 0.5 * in_object / objects;
                    break;
                }
                case LightSelection::Power:
                    p = by_power;
                    break;
                case LightSelection::Uniform:
                    break;
            }
            probability_[mode][i] = static_cast<float>(p);
            running += p;
            cdf_[mode][i] = static_cast<float>(running);
        }
        if (!cdf_[mode].empty()) cdf_[mode].back() = 1.0f;
    }
}

uint32_t LightSet::choose(float u, LightSelection selection) const {
    if (lights_.empty()) return 0;
    const std::vector<float>& cdf = cdf_[static_cast<size_t>(selection)];
    const auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
    return static_cast<uint32_t>(std::min(static_cast<size_t>(it - cdf.begin()), lights_.size() - 1));
}

bool LightSet::sample(Vec3 p, Vec3 n, float u_choice, Vec2 u, LightSample* out, LightSelection selection,
                      TriangleSampling triangle) const {
    if (lights_.empty()) return false;
    const uint32_t index = choose(u_choice, selection);
    const float choice = probability(index, selection);
    if (!(choice > 0.0f)) return false;
    const bool ok = std::visit(
        [&](const auto& l) {
            using T = std::decay_t<decltype(l)>;
            if constexpr (std::is_same_v<T, SunLight> || std::is_same_v<T, EnvironmentLight>) {
                return l.sample(u, out);
            } else if constexpr (std::is_same_v<T, EmissiveTriangle>) {
                return l.sample(p, n, u, out, triangle);
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

float LightSet::emissive_triangle_pdf(uint32_t index, Vec3 p, Vec3 n, Vec3 hit, LightSelection selection,
                                      TriangleSampling triangle) const {
    const auto& tri = std::get<EmissiveTriangle>(lights_[index]);
    return probability(index, selection) * tri.pdf(p, n, hit, triangle);
}

Rgb LightSet::lamp_radiance(Vec3 origin, Vec3 dir, float t_max, uint32_t visibility, float* pdf, float* t_out,
                            LightSelection selection) const {
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
            nearest_pdf = probability(i, selection) * solid_angle_pdf;
        }
    }
    if (pdf) *pdf = nearest_pdf;
    if (t_out) *t_out = nearest;
    return radiance;
}

const EnvironmentLight* LightSet::environment() const {
    return environment_ == SIZE_MAX ? nullptr : &std::get<EnvironmentLight>(lights_[environment_]);
}

float LightSet::environment_pdf(Vec3 wi, LightSelection selection) const {
    if (environment_ == SIZE_MAX) return 0.0f;
    return probability(static_cast<uint32_t>(environment_), selection) *
           std::get<EnvironmentLight>(lights_[environment_]).pdf(wi);
}

bool LightSet::sample_emission(float u_choice, Vec2 u_position, Vec2 u_direction, LightSelection selection,
                               Vec3 center, float radius, EmissionSample* out) const {
    if (lights_.empty()) return false;
    const uint32_t index = choose(u_choice, selection);
    const float choice = probability(index, selection);
    if (!(choice > 0.0f)) return false;
    const bool ok = std::visit(
        [&](const auto& l) {
            using T = std::decay_t<decltype(l)>;
            if constexpr (std::is_same_v<T, SunLight> || std::is_same_v<T, EnvironmentLight>) {
                return l.sample_emission(u_position, u_direction, center, radius, out);
            } else if constexpr (std::is_same_v<T, PointLight> || std::is_same_v<T, SpotLight>) {
                l.sample_emission(u_direction, out);
                return true;
            } else if constexpr (std::is_same_v<T, AreaLight>) {
                l.sample_emission(u_position, u_direction, out);
                return true;
            } else {
                return l.sample_emission(u_position, u_direction, out);
            }
        },
        lights_[index]);
    if (!ok || out->weight.is_black()) return false;
    out->weight = out->weight * (1.0f / choice);
    out->visibility = visibility_[index];
    return true;
}

}  // namespace stratum
