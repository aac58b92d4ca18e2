#include "lights/light_set.h"

#include <algorithm>
#include <unordered_map>

namespace stratum {

uint32_t LightSet::add(std::unique_ptr<const Light> light, uint32_t object, uint32_t visibility) {
    const auto index = static_cast<uint32_t>(lights_.size());
    if (light->is_hittable_lamp()) hittable_lamps_.push_back(index);
    if (light->is_delta()) ++delta_lights_;
    lights_.push_back(std::move(light));
    object_.push_back(object);
    visibility_.push_back(visibility);
    return index;
}

uint32_t LightSet::add_environment(EnvironmentLight environment, uint32_t object) {
    auto light = std::make_unique<const EnvironmentLight>(std::move(environment));
    environment_ = light.get();
    environment_index_ = add(std::move(light), object);
    return environment_index_;
}

void LightSet::finalize(float scene_radius) {
    std::vector<double> power(lights_.size());
    for (size_t i = 0; i < lights_.size(); ++i) power[i] = lights_[i]->power(scene_radius);
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
    if (!lights_[index]->sample(p, n, u, triangle, out)) return false;
    out->pdf *= choice;
    out->visibility = visibility_[index];
    return true;
}

float LightSet::emissive_triangle_pdf(uint32_t index, Vec3 p, Vec3 n, Vec3 hit, LightSelection selection,
                                      TriangleSampling triangle) const {
    const auto& tri = static_cast<const EmissiveTriangle&>(*lights_[index]);
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
        if (lights_[i]->intersect(origin, dir, nearest, &t, &L, &solid_angle_pdf)) {
            nearest = t;
            radiance = L;
            nearest_pdf = probability(i, selection) * solid_angle_pdf;
        }
    }
    if (pdf) *pdf = nearest_pdf;
    if (t_out) *t_out = nearest;
    return radiance;
}

float LightSet::environment_pdf(Vec3 wi, LightSelection selection) const {
    if (!environment_) return 0.0f;
    return probability(environment_index_, selection) * environment_->pdf(wi);
}

bool LightSet::sample_emission(float u_choice, Vec2 u_position, Vec2 u_direction, LightSelection selection,
                               Vec3 center, float radius, EmissionSample* out) const {
    if (lights_.empty()) return false;
    const uint32_t index = choose(u_choice, selection);
    const float choice = probability(index, selection);
    if (!(choice > 0.0f)) return false;
    if (!lights_[index]->sample_emission(u_position, u_direction, center, radius, out)) return false;
    if (out->weight.is_black()) return false;
    out->weight = out->weight * (1.0f / choice);
    out->visibility = visibility_[index];
    return true;
}

}  // namespace stratum
