// Benchmarks registered at run time, from lists only known then (the sampler registry).
#pragma once

namespace stratum::bench {

// One 1D and one 2D benchmark per sampler of sampler_registry() (bench_samplers.cpp).
void register_sampler_benchmarks();

}  // namespace stratum::bench
