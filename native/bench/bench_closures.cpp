// Evaluations and samples per second of the closure models the integrators call most (through
// bsdf_eval / bsdf_sample, the models' registry entries): Lambert, Principled v1 (Cycles 3.x),
// Principled v2 (Cycles 4.x) and rough glass, each for 4096 fixed (wo, wi) pairs and samples.
#include <benchmark/benchmark.h>

#include "bench_inputs.h"
#include "bsdf/bsdf.h"
#include "stratum/stratum.h"

namespace stratum::bench {
namespace {

Material material(StratumMaterialModel model, float roughness, float ior) {
    Material m{};
    m.model = model;
    m.base_color = Rgb(0.8f, 0.6f, 0.4f);
    m.roughness = roughness;
    m.metallic = 0.0f;
    m.specular = 0.5f;
    m.ior = ior;
    m.emission = Rgb(0.0f);
    m.distribution = MicrofacetDistribution::Ggx;
    return m;
}

const Material kLambert = material(STRATUM_MATERIAL_DIFFUSE, 0.0f, 1.45f);
const Material kPrincipledV1 = material(STRATUM_MATERIAL_PRINCIPLED_V1, 0.4f, 1.45f);
const Material kPrincipledV2 = material(STRATUM_MATERIAL_PRINCIPLED_V2, 0.4f, 1.5f);
// Rough, so that eval is not the zero of a delta lobe.
const Material kGlass = material(STRATUM_MATERIAL_GLASS, 0.3f, 1.45f);

void eval(benchmark::State& state, const Material* m) {
    const std::vector<Vec3> wo = upper_directions(1), wi = upper_directions(2);
    size_t i = 0;
    float sum = 0.0f;
    for (auto _ : state) {
        const BsdfEval e = bsdf_eval(*m, wo[i], wi[i]);
        sum += e.value.r + e.pdf;
        i = (i + 1) & (kInputs - 1);
    }
    benchmark::DoNotOptimize(sum);
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}

void sample(benchmark::State& state, const Material* m) {
    const std::vector<Vec3> wo = upper_directions(3);
    const std::vector<Vec2> u = uniform_pairs(4), u_lobe = uniform_pairs(5);
    size_t i = 0;
    float sum = 0.0f;
    for (auto _ : state) {
        BsdfSample s;
        if (bsdf_sample(*m, wo[i], u_lobe[i].x, u[i], &s)) sum += s.weight.r + s.wi.z;
        i = (i + 1) & (kInputs - 1);
    }
    benchmark::DoNotOptimize(sum);
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}

BENCHMARK_CAPTURE(eval, lambert, &kLambert);
BENCHMARK_CAPTURE(eval, principled_v1, &kPrincipledV1);
BENCHMARK_CAPTURE(eval, principled_v2, &kPrincipledV2);
BENCHMARK_CAPTURE(eval, glass, &kGlass);
BENCHMARK_CAPTURE(sample, lambert, &kLambert);
BENCHMARK_CAPTURE(sample, principled_v1, &kPrincipledV1);
BENCHMARK_CAPTURE(sample, principled_v2, &kPrincipledV2);
BENCHMARK_CAPTURE(sample, glass, &kGlass);

}  // namespace
}  // namespace stratum::bench
