// The radiosity method's settings (textbook §3; the `radiosity` integrator,
// integrators/radiosity_integrator.h), as render settings reach it.
//
// | setting             | meaning                                                             |
// |---------------------|---------------------------------------------------------------------|
// | radiosity_patch_size| longest edge a patch may have (scene units); 0 = automatic: the     |
// |                     | diagonal of the scene's bounding box / kAutomaticPatchDivisions     |
// | radiosity_solver    | shooting (progressive, brightest unshot first), gauss_seidel, jacobi|
// | radiosity_tolerance | the solve stops when the book's ΔE is at most this share of the     |
// |                     | scene's mean radiance                                               |
// | radiosity_rays      | cosine-distributed rays per patch that estimate its form factors    |
//
// Why the automatic patch size is diag/32: K grows as (extent / size)², so a size proportional
// to the scene's extent gives the same K whatever the units. A cube room of side s has diagonal
// s√3, so size = s√3/32 splits each face's two triangles (longest edge s√2) into
// ⌊32√2/√3⌋ + 1 = 27 parts per edge, 729 patches each: 2 × 6 × 729 × 2 sides = 17,496 patches,
// about 4.5 M form-factor rays at 256 rays and at most 36 MB of form factors (twice that while
// shooting, which also holds their transpose). The default tolerance 1e-3 is the accuracy the
// book finds Monte Carlo rarely beats (claim 13, 0.1 %).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "core/registry.h"

namespace stratum {

// Menu order (default first): a host stores a choice by its position, so never reorder.
enum class RadiositySolver : uint8_t { Shooting = 0, GaussSeidel = 1, Jacobi = 2 };

struct RadiositySettings {
    float patch_size = 0.0f;  // 0 = automatic
    RadiositySolver solver = RadiositySolver::Shooting;
    float tolerance = 1e-3f;
    uint32_t rays = 256;
    bool operator==(const RadiositySettings&) const = default;
};

inline constexpr float kAutomaticPatchDivisions = 32.0f;
// The largest radiosity_rays: hit counts of one row stay exact in float (< 2^24).
inline constexpr uint32_t kMaxRadiosityRays = 1u << 20;

std::span<const RegistryEntry> radiosity_solver_choices();

}  // namespace stratum
