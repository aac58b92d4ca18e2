// What every light model returns to the light tracer when it emits a particle (textbook §6:
// estimator 6.2 with the source pdfs 6.3–6.5).
//
// | field       | meaning                                                                     |
// |-------------|-----------------------------------------------------------------------------|
// | position    | where the particle starts: on the emitter, or on a disk outside the scene   |
// |             | (sun, environment)                                                          |
// | direction   | unit direction of flight                                                    |
// | normal      | emitting surface's normal on the side the particle leaves; 0 for points     |
// | weight      | the flux the particle carries: L_e |cos θ|/(p_A p_ω) (area, 6.3), I(Θ)/p_ω  |
// |             | (point, 6.4), E/p_A (parallel, 6.5); LightSet divides by the choice p_j      |
// | soft_radius | Cycles' facing-disk radius r of a point / spot lamp (0 otherwise): the first |
// |             | hit at distance d takes d²/(d² + r²)                                        |
// | program     | the lamp's program, or null: the first hit at distance d takes its scale(d) |
#pragma once

#include "core/math.h"
#include "scene/visibility.h"

namespace stratum {

class LampProgram;

struct EmissionSample {
    Vec3 position;
    Vec3 direction;
    Vec3 normal{0.0f, 0.0f, 0.0f};
    Rgb weight;
    float soft_radius = 0.0f;
    // StratumVisibility bits of the light (set by LightSet::sample_emission).
    uint32_t visibility = kVisibleAll;
    const LampProgram* program = nullptr;
};

}  // namespace stratum
