// stratum_microbench: Google Benchmark micro-benchmarks of the renderer's inner loops (issue 15,
// target 2), one file per area: samplers (bench_samplers.cpp), closures (bench_closures.cpp),
// lights and the spherical triangle (bench_lights.cpp), the film (bench_film.cpp). Every
// benchmark reports items/s: values, evaluations, samples or film additions per second.
// How to run it and read it: docs/performance.md, "Micro-benchmarks".
#include <benchmark/benchmark.h>

#include "bench_registration.h"

int main(int argc, char** argv) {
    // The samplers are listed at run time (sampler_registry), so they are registered here rather
    // than by static BENCHMARK macros.
    stratum::bench::register_sampler_benchmarks();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
