// How StratumVisibility bits follow a path, shared by the path and light tracers: the bit a
// scattered ray carries (Cycles' PATH_RAY_DIFFUSE / GLOSSY / TRANSMISSION), and the closure kinds
// a light's bits let it light directly (Cycles' light visibility).
#pragma once

#include <cstdint>

#include "bsdf/closure_set.h"
#include "scene/visibility.h"
#include "shading/light_path_state.h"

namespace stratum {

// The ray visibility bit of a ray scattered by a lobe of this kind.
inline uint32_t ray_visibility(ScatterKind kind, uint32_t previous) {
    switch (kind) {
        case ScatterKind::Diffuse:
            return kVisibleDiffuse;
        case ScatterKind::Glossy:
            return kVisibleGlossy;
        case ScatterKind::Transmission:
            return kVisibleTransmission;
        case ScatterKind::Transparent:
            break;  // a pass-through keeps the kind of the ray that arrived
    }
    return previous;
}

// The kind of a ray scattered by a lobe of this kind (delta: a smooth lobe), as Cycles'
// path_state_next sets the path flag (LightPathRay bits): a reflection is REFLECT and DIFFUSE or
// GLOSSY, a refraction TRANSMIT and GLOSSY, a smooth one also SINGULAR. A transparent
// pass-through keeps the arriving ray's kind.
inline uint32_t light_path_rays(ScatterKind kind, bool delta, uint32_t previous) {
    const uint32_t singular = delta ? uint32_t{kLightPathSingular} : 0u;
    switch (kind) {
        case ScatterKind::Diffuse:
            return kLightPathReflection | kLightPathDiffuse;
        case ScatterKind::Glossy:
            return kLightPathReflection | kLightPathGlossy | singular;
        case ScatterKind::Transmission:
            return kLightPathTransmission | kLightPathGlossy | singular;
        case ScatterKind::Transparent:
            break;
    }
    return previous;
}

// The closure kinds (scatter_kind_bit) a light with these visibility bits lights directly.
inline uint32_t lit_kinds(uint32_t light_visibility) {
    uint32_t kinds = 0;
    if (light_visibility & kVisibleDiffuse) kinds |= scatter_kind_bit(ScatterKind::Diffuse);
    if (light_visibility & kVisibleGlossy) kinds |= scatter_kind_bit(ScatterKind::Glossy);
    if (light_visibility & kVisibleTransmission) kinds |= scatter_kind_bit(ScatterKind::Transmission);
    return kinds;
}

}  // namespace stratum
