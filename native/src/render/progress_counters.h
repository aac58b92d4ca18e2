// The named counters of a render's progress: what a feature reports beyond the generic
// progress (samples, rays, times), one counter per quantity, named "feature.quantity". The ABI
// lists them by position (stratum_renderer_progress_counter) and hosts find them by name, so a
// feature that reports something adds a counter at the end of both lists below, and no field.
//
// | counter              | value; 0 when the render does not use the feature                    |
// |----------------------|-----------------------------------------------------------------------|
// | light_tree.seconds   | the light tree the render chooses lights by: its build, with the      |
// | light_tree.bytes     | lights' bounds, and the bytes it holds (LightSet::tree_report)        |
// | radiosity.patches    | the radiosity integrator's solve: patches K, the most bytes it held   |
// | radiosity.bytes      | at once, its seconds (form factors and solver) and the solver's       |
// | radiosity.seconds    | iterations (RadiosityReport)                                          |
// | radiosity.iterations |                                                                       |
// | guiding.nodes        | path guiding's tree after the last training pass: its nodes and bytes |
// | guiding.bytes        | (GuidingReport)                                                       |
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace stratum {

enum class ProgressCounter : uint32_t {
    LightTreeSeconds,
    LightTreeBytes,
    RadiosityPatches,
    RadiosityBytes,
    RadiositySeconds,
    RadiosityIterations,
    GuidingNodes,
    GuidingBytes,
};

// The counters' names, in ProgressCounter's order.
inline constexpr std::array kProgressCounterNames = {
    "light_tree.seconds", "light_tree.bytes",     "radiosity.patches", "radiosity.bytes",
    "radiosity.seconds",  "radiosity.iterations", "guiding.nodes",     "guiding.bytes",
};
static_assert(static_cast<size_t>(ProgressCounter::GuidingBytes) + 1 == kProgressCounterNames.size(),
              "every ProgressCounter has a name");

// One render's counters: by ProgressCounter, or by position as the ABI lists them.
struct ProgressCounters {
    std::array<double, kProgressCounterNames.size()> values{};

    double& operator[](ProgressCounter c) { return values[static_cast<size_t>(c)]; }
    double operator[](ProgressCounter c) const { return values[static_cast<size_t>(c)]; }
};

}  // namespace stratum
