// Film::add_sample per second: a camera sample's radiance and alpha added to its pixel's exact
// fixed-point sums (film/film.h), without passes (the default render) and with the Normal,
// Depth and Stratum Error passes (an Average, a FirstSample and the squared-radiance sums).
#include <benchmark/benchmark.h>

#include <vector>

#include "bench_inputs.h"
#include "film/film.h"

namespace stratum::bench {
namespace {

void add_sample(benchmark::State& state, std::vector<Pass> passes) {
    const Film film(PixelRegion{0, 0, 64, 64}, 64, 64, PixelFilter(FilterType::Box, 1.0f), passes,
                    /*light_paths=*/false);
    std::vector<FilmSum> sums(film.sums_stride(), 0);
    const std::vector<Vec2> rg = uniform_pairs(31);
    const std::vector<float> values(film.layout().extra_channels() + 1, 0.5f);
    size_t i = 0;
    uint32_t index = 0;
    bool clamped = false;
    for (auto _ : state) {
        clamped |= film.add_sample(sums.data(), index++, Rgb(rg[i].x, rg[i].y, 0.5f), 1.0f, values.data());
        i = (i + 1) & (kInputs - 1);
    }
    benchmark::DoNotOptimize(clamped);
    benchmark::DoNotOptimize(sums.data());
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}
BENCHMARK_CAPTURE(add_sample, combined, std::vector<Pass>{});
BENCHMARK_CAPTURE(add_sample, normal_depth_error, std::vector<Pass>{Pass::Normal, Pass::Depth, Pass::Error});

}  // namespace
}  // namespace stratum::bench
