#include "radiosity/lamp_irradiance.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "lights/emissive_triangle.h"
#include "radiosity/form_factors.h"
#include "sampling/sobol_sampler.h"
#include "sampling/warps.h"

namespace stratum {

std::vector<uint32_t> radiosity_lamps(const RenderScene& scene) {
    const LightSet& lights = scene.lights();
    std::vector<uint32_t> lamps;
    for (uint32_t l = 0; l < lights.size(); ++l) {
        const Light& light = lights.light(l);
        if (dynamic_cast<const EmissiveTriangle*>(&light) || &light == lights.environment()) continue;
        if (!(lights.visibility(l) & kVisibleDiffuse)) continue;
        lamps.push_back(l);
    }
    return lamps;
}

LampIrradiance lamp_irradiance(const RenderScene& scene, const PatchSet& patches,
                               const std::atomic<bool>* cancel) {
    LampIrradiance out;
    const std::vector<uint32_t> lamps = radiosity_lamps(scene);
    if (lamps.empty()) return out;
    const LightSet& lights = scene.lights();
    // The choice among lamps by power: cumulative shares (uniform when all are 0).
    std::vector<double> cdf(lamps.size());
    double total = 0.0;
    for (size_t k = 0; k < lamps.size(); ++k) total += std::max(lights.power(lamps[k]), 0.0);
    double running = 0.0;
    std::vector<float> probability(lamps.size());
    for (size_t k = 0; k < lamps.size(); ++k) {
        const double p = total > 0.0 ? std::max(lights.power(lamps[k]), 0.0) / total
                                     : 1.0 / static_cast<double>(lamps.size());
        probability[k] = static_cast<float>(p);
        running += p;
        cdf[k] = running;
    }
    const uint32_t count = patches.size();
    out.irradiance.assign(count, Rgb(0.0f));
    const SobolSampler sampler(SamplerSettings{kLampSamples, kLampSeed, 1, 1});
    const RayQuery query{0.0f, kVisibleShadow};
    tbb::parallel_for(
        tbb::blocked_range<uint32_t>(0, count, 256), [&](const tbb::blocked_range<uint32_t>& range) {
            if (cancel && cancel->load(std::memory_order_relaxed)) return;
            for (uint32_t i = range.begin(); i != range.end(); ++i) {
                const Patch& patch = patches.patch(i);
                Rgb sum(0.0f);
                for (uint32_t s = 0; s < kLampSamples; ++s) {
                    const PixelSample ps(i & 0xffffu, i >> 16, s);
                    const Vec3 point = patch.point(sample_uniform_triangle(sampler.get_2d(ps, 0)));
                    const double u = sampler.get_1d(ps, 4);
                    const size_t k =
                        std::min(static_cast<size_t>(std::upper_bound(cdf.begin(), cdf.end(), u * running) -
                                                     cdf.begin()),
                                 lamps.size() - 1);
                    if (!(probability[k] > 0.0f)) continue;
                    LightSample ls;
                    if (!lights.light(lamps[k]).sample(point, patch.normal, sampler.get_2d(ps, 2),
                                                       TriangleSampling::SolidAngle, &ls) ||
                        !(ls.pdf > 0.0f))
                        continue;
                    const float cosine = dot(ls.wi, patch.normal);
                    if (!(cosine > 0.0f)) continue;
                    const Vec3 origin = patch_ray_origin(point, patch.normal);
                    if (lights.visibility(lamps[k]) & kVisibleShadow) {
                        const float t_max =
                            std::isfinite(ls.distance)
                                ? std::max(0.0f,
                                           ls.distance - 2.0f * patch_ray_offset(point + ls.wi * ls.distance))
                                : kInfinity;
                        if (scene.occluded(origin, ls.wi, 0.0f, t_max, query)) continue;
                    }
                    sum += ls.radiance * (cosine / (ls.pdf * probability[k]));
                }
                out.irradiance[i] = sum * (1.0f / static_cast<float>(kLampSamples));
            }
        });
    if (cancel && cancel->load(std::memory_order_relaxed)) throw RenderScene::BuildCancelled();
    out.rays = static_cast<uint64_t>(count) * kLampSamples;
    return out;
}

}  // namespace stratum
