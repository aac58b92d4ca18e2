// Values per second of every sampler of the registry, through the Sampler interface (a virtual
// call per value, as the integrators make them), in the access pattern of a path tracer: each
// sample index of each pixel of a 32 × 32 tile at 64 samples per pixel reads the dimensions
// 0 .. 21 in order (the camera block and two bounces of dimensions.h), as 22 get_1d or 11 get_2d.
#include <benchmark/benchmark.h>

#include <string>

#include "bench_registration.h"
#include "sampling/sampler_registry.h"

namespace stratum::bench {
namespace {

constexpr uint32_t kTile = 32, kSamples = 64, kDimensions = 22;

// Samplers that build tables on first use (bluenoise) build them here, before the clock runs.
void warm_up(const Sampler& sampler) {
    float sum = 0.0f;
    const PixelSample s(0, 0, 0);
    for (uint32_t d = 0; d < kDimensions; ++d) sum += sampler.get_1d(s, d);
    for (uint32_t d = 0; d < kDimensions; d += 2) sum += sampler.get_2d(s, d).x;
    benchmark::DoNotOptimize(sum);
}

SamplerSettings settings() {
    return SamplerSettings{kSamples, /*seed=*/1, /*width=*/kTile, /*height=*/kTile};
}

// Walks the tile's (pixel, index) pairs, one per iteration of the benchmark loop (a
// PixelSample, with its hashed keys, is made once per sample as the renderer makes it).
struct SampleWalk {
    PixelSample next() {
        const PixelSample s(x, y, index);
        if (++index == kSamples) {
            index = 0;
            if (++x == kTile) {
                x = 0;
                y = (y + 1) % kTile;
            }
        }
        return s;
    }
    uint32_t x = 0, y = 0, index = 0;
};

void values_1d(benchmark::State& state, const SamplerEntry* entry) {
    const std::unique_ptr<Sampler> sampler = entry->create(settings());
    warm_up(*sampler);
    SampleWalk walk;
    float sum = 0.0f;
    for (auto _ : state) {
        const PixelSample s = walk.next();
        for (uint32_t d = 0; d < kDimensions; ++d) sum += sampler->get_1d(s, d);
    }
    benchmark::DoNotOptimize(sum);
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * kDimensions);
}

void values_2d(benchmark::State& state, const SamplerEntry* entry) {
    const std::unique_ptr<Sampler> sampler = entry->create(settings());
    warm_up(*sampler);
    SampleWalk walk;
    float sum = 0.0f;
    for (auto _ : state) {
        const PixelSample s = walk.next();
        for (uint32_t d = 0; d < kDimensions; d += 2) {
            const Vec2 v = sampler->get_2d(s, d);
            sum += v.x + v.y;
        }
    }
    benchmark::DoNotOptimize(sum);
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * kDimensions);
}

}  // namespace

void register_sampler_benchmarks() {
    for (const SamplerEntry& entry : sampler_registry()) {
        const std::string name(entry.info.name);
        benchmark::RegisterBenchmark(("Sampler1d/" + name).c_str(), values_1d, &entry);
        benchmark::RegisterBenchmark(("Sampler2d/" + name).c_str(), values_2d, &entry);
    }
}

}  // namespace stratum::bench
