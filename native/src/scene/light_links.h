// Light linking and shadow linking (Blender 4.0+; Cycles' KernelObject fields of the same
// names, set by Blender's depsgraph, source/blender/depsgraph/intern/depsgraph_light_linking.cc).
// The host computes the sets (addon/stratum/export/light_linking.py); this is what an object
// carries of them.
//
// | field                 | role of the object | meaning                                          |
// |-----------------------|--------------------|--------------------------------------------------|
// | receiver_light_set    | lit surface        | its light set id, 0..63 (0: listed by no emitter)|
// | blocker_shadow_set    | occluder           | its shadow set id, 0..63 (0: listed by none)     |
// | light_set_membership  | emitter            | bit s set: lights receivers of light set s       |
// | shadow_set_membership | emitter            | bit s set: occluders of shadow set s cast its    |
// |                       |                    | shadows; any other occluder is ignored           |
//
// Cycles' tests (light/light.h light_link_light_match, bvh/util.h
// intersection_skip_shadow_link): an emitter lights a receiver iff bit receiver_light_set of its
// light_set_membership is set, and an occluder blocks an emitter iff bit blocker_shadow_set of the
// emitter's shadow_set_membership is set. An emitter whose shadow_set_membership is not all sets
// is "shadow-linked": forward paths reach it through a dedicated pass (integrators/shadow_linking.h).
#pragma once

#include <cstdint>

namespace stratum {

inline constexpr uint64_t kAllLinkSets = ~uint64_t{0};
inline constexpr uint32_t kMaxLinkSet = 63;

struct LightLinks {
    uint8_t receiver_light_set = 0;
    uint8_t blocker_shadow_set = 0;
    uint64_t light_set_membership = kAllLinkSets;
    uint64_t shadow_set_membership = kAllLinkSets;

    bool lights(uint8_t receiver_set) const { return (light_set_membership >> receiver_set) & 1u; }
    bool shadow_linked() const { return shadow_set_membership != kAllLinkSets; }
};

}  // namespace stratum
