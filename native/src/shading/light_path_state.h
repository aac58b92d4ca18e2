// What Cycles' Light Path node (kernel/svm/light_path.h, the same in 3.4 and 5.0) reads of the
// path that reaches a shading point: the path flag's ray kinds and the path state's bounce
// counters, as the integrators fill them in each context (docs/cycles_models.md "Light Path
// node").
//
// | register                 | value                                                        |
// |--------------------------|--------------------------------------------------------------|
// | IS_*_RAY                 | 1 where the matching bit of `rays` is set, else 0            |
// | RAY_DEPTH                | `depth`: the arriving bounce, +1 on shadow rays, lamps and   |
// |                          | the world (Cycles adds 1 under PATH_RAY_SHADOW | EMISSION)   |
// | DIFFUSE / GLOSSY /       | the counters of Cycles' path state (shadow_path's on a       |
// | TRANSPARENT /            | shadow ray, whose transparent counter also counts the        |
// | TRANSMISSION_DEPTH       | surfaces it crossed before this one)                         |
// | PORTAL_DEPTH             | 0: Stratum has no Ray Portal BSDF                            |
#pragma once

#include <cstddef>
#include <cstdint>

#include "shading/node_registry.h"
#include "shading/program_layout.h"
#include "shading/shader_program.h"

namespace stratum {

// Cycles' PATH_RAY_* visibility bits the node reads, in the order of its outputs.
enum LightPathRay : uint32_t {
    kLightPathCamera = 1u << 0,
    kLightPathShadow = 1u << 1,
    kLightPathDiffuse = 1u << 2,
    kLightPathGlossy = 1u << 3,
    kLightPathSingular = 1u << 4,
    kLightPathReflection = 1u << 5,
    kLightPathTransmission = 1u << 6,
    kLightPathVolumeScatter = 1u << 7,
};

struct LightPathState {
    uint32_t rays = 0;  // LightPathRay bits
    uint32_t depth = 0, diffuse = 0, glossy = 0, transparent = 0, transmission = 0;

    // Writes the node's 14 registers (shader_input::kIsCameraRay .. kPortalDepth).
    void write(float* registers) const {
        for (uint32_t k = 0; k < 8; ++k)
            registers[shader_input::kIsCameraRay + k] = (rays >> k) & 1u ? 1.0f : 0.0f;
        registers[shader_input::kRayDepth] = static_cast<float>(depth);
        registers[shader_input::kDiffuseDepth] = static_cast<float>(diffuse);
        registers[shader_input::kGlossyDepth] = static_cast<float>(glossy);
        registers[shader_input::kTransparentDepth] = static_cast<float>(transparent);
        registers[shader_input::kTransmissionDepth] = static_cast<float>(transmission);
        registers[shader_input::kPortalDepth] = 0.0f;
    }
    // The same path evaluated with Cycles' PATH_RAY_EMISSION alone (a lamp or the world for a
    // light sample, a lamp a ray meets): no ray kind, one bounce further.
    LightPathState emission() const { return {0u, depth + 1, diffuse, glossy, transparent, transmission}; }
    // The world met by this path's ray: Cycles evaluates it with the ray's flags and
    // PATH_RAY_EMISSION, so the ray kinds stay and it is one bounce further.
    LightPathState background() const {
        return {rays, depth + 1, diffuse, glossy, transparent, transmission};
    }
    // A shadow ray of this path that has crossed `crossed` transparent surfaces before this one
    // (Cycles' shadow_path: PATH_RAY_SHADOW alone, one bounce further).
    LightPathState shadow(uint32_t crossed) const {
        return {kLightPathShadow, depth + 1, diffuse, glossy, transparent + crossed, transmission};
    }
};

// What a lamp or the world sees as the direct light of a camera ray's first hit (the emission
// evaluation of a path at depth 0), and where an integrator follows no Cycles path.
inline constexpr LightPathState kDirectLightPath{0u, 1u, 0u, 0u, 0u, 0u};

// Whether a register is one of the Light Path node's.
inline bool is_light_path_input(uint32_t reg) {
    return reg >= shader_input::kIsCameraRay && reg <= shader_input::kPortalDepth;
}

// Whether a node of `program` (checked: its types are known) reads one of the Light Path node's
// inputs.
inline bool reads_light_path(const ShaderProgram& program) {
    for (const ShaderNode& n : program.nodes) {
        const NodeEntry& entry = *node_entry(n.type);
        for (size_t k = 0; k < n.inputs.size(); ++k) {
            const uint32_t width = entry.input_widths[k];
            if (width > 0 && n.inputs[k] <= shader_input::kPortalDepth &&
                n.inputs[k] + width > shader_input::kIsCameraRay)
                return true;
        }
    }
    return false;
}

}  // namespace stratum
