#include "sampling/sampler_registry.h"

#include <array>

#include "sampling/bluenoise_sampler.h"
#include "sampling/fibonacci_sampler.h"
#include "sampling/halton_sampler.h"
#include "sampling/independent_sampler.h"
#include "sampling/lcg_sampler.h"
#include "sampling/lhs_sampler.h"
#include "sampling/sobol_sampler.h"
#include "sampling/stratified_sampler.h"
#include "sampling/zsobol_sampler.h"

namespace stratum {

namespace {

template <typename T>
std::unique_ptr<Sampler> make(const SamplerSettings& settings) {
    return std::make_unique<T>(settings);
}

const std::array kSamplers = {
    SamplerEntry{{"random", "Random (PCG32)",
                  "Independent uniform samples: PCG32 keyed by a hash of pixel, sample, dimension and seed"},
                 &make<IndependentSampler>,
                 SampleStructure::Independent},
    SamplerEntry{
        {"lcg", "LCG (minstd)",
         "The coursework's standard generator: minstd LCG seeded by a hash of pixel, sample and dimension"},
        &make<LcgSampler>,
        SampleStructure::Independent},
    SamplerEntry{{"stratified", "Stratified (jittered)",
                  "Jittered grid per dimension pair: one random point in each cell of a shuffled grid of the "
                  "sample count"},
                 &make<StratifiedSampler>,
                 SampleStructure::WholeCount},
    SamplerEntry{
        {"lhs", "Latin hypercube",
         "N-rooks: each dimension split into as many strata as samples, one jittered sample per stratum"},
        &make<LhsSampler>,
        SampleStructure::WholeCount},
    SamplerEntry{{"halton", "Halton",
                  "Halton sequence (one prime base per dimension), each pixel a stratified run of it"},
                 &make<PlainHaltonSampler>,
                 SampleStructure::Progressive},
    SamplerEntry{{"halton_rd", "Halton (random digits)",
                  "Halton with every digit of each base passed through a random permutation"},
                 &make<PermutedHaltonSampler>,
                 SampleStructure::Progressive},
    SamplerEntry{
        {"halton_owen", "Halton (Owen)",
         "Halton with base-b Owen scrambling: each digit permuted depending on the digits before it"},
        &make<OwenHaltonSampler>,
        SampleStructure::Progressive},
    SamplerEntry{
        {"sobol", "Sobol (Owen-scrambled)",
         "Owen-scrambled Sobol per pixel and dimension pair (Burley 2020); best with power-of-two samples"},
        &make<SobolSampler>,
        SampleStructure::Progressive},
    SamplerEntry{
        {"zsobol", "Sobol (blue-noise pixels)",
         "Sobol ordered over the image in Z-order so pixel errors form blue noise (Ahmed & Wonka 2020)"},
        &make<ZSobolSampler>,
        SampleStructure::Progressive,
        true},
    SamplerEntry{{"bluenoise", "Blue noise (void-and-cluster)",
                  "Values read from a 128x128 void-and-cluster texture so neighbouring pixels' errors form "
                  "blue noise"},
                 &make<BlueNoiseSampler>,
                 SampleStructure::Progressive,
                 true},
    SamplerEntry{
        {"fibonacci", "Fibonacci lattice",
         "Fibonacci lattice of the sample count per dimension pair, randomly shifted in every pixel"},
        &make<FibonacciSampler>,
        SampleStructure::WholeCount},
    SamplerEntry{{"fibonacci_static", "Fibonacci lattice (static)",
                  "Fibonacci lattice, same shift in every pixel (banding, seed 000 table 3)"},
                 &make<StaticFibonacciSampler>,
                 SampleStructure::WholeCount},
};

}  // namespace

std::span<const SamplerEntry> sampler_registry() { return kSamplers; }

const SamplerEntry* find_sampler(std::string_view name) {
    for (const SamplerEntry& e : kSamplers) {
        if (name == e.info.name) return &e;
    }
    return nullptr;
}

}  // namespace stratum
