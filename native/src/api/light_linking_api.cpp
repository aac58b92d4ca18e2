// stratum_scene_set_light_linking (stratum/scene.h): the light and shadow linking sets of
// instances and lamps (scene/light_links.h), checked here.
#include <cstdint>
#include <string>

#include "api/abi_guard.h"
#include "api/scene_handle.h"
#include "scene/scene.h"
#include "stratum/stratum.h"

namespace {

using stratum::require;
using stratum::abi::guarded;

// A set id names one of the 64 bits of a membership.
void check_set_ids(const uint8_t* ids, uint32_t count, const char* name) {
    for (uint32_t k = 0; ids && k < count; ++k)
        require(ids[k] <= STRATUM_MAX_LINK_SET, std::string(name) + "[" + std::to_string(k) +
                                                    "] = " + std::to_string(ids[k]) + " is more than " +
                                                    std::to_string(STRATUM_MAX_LINK_SET));
}

// Writes element k of the arrays given into `links`.
void assign(stratum::LightLinks& links, uint32_t k, const uint8_t* receiver, const uint8_t* blocker,
            const uint64_t* light, const uint64_t* shadow) {
    if (receiver) links.receiver_light_set = receiver[k];
    if (blocker) links.blocker_shadow_set = blocker[k];
    if (light) links.light_set_membership = light[k];
    if (shadow) links.shadow_set_membership = shadow[k];
}

}  // namespace

extern "C" {

StratumStatus stratum_scene_set_light_linking(StratumScene* scene, int32_t target, uint32_t first,
                                              uint32_t count, const uint8_t* receiver_light_set,
                                              const uint8_t* blocker_shadow_set,
                                              const uint64_t* light_set_membership,
                                              const uint64_t* shadow_set_membership) {
    return guarded("stratum_scene_set_light_linking", [&] {
        require(scene != nullptr, "scene is NULL");
        require(target == STRATUM_LINK_INSTANCES || target == STRATUM_LINK_LIGHTS,
                "target = " + std::to_string(target) + " is not a StratumLinkTarget (0 instances, 1 lights)");
        check_set_ids(receiver_light_set, count, "receiver_light_set");
        check_set_ids(blocker_shadow_set, count, "blocker_shadow_set");
        const bool lamps = target == STRATUM_LINK_LIGHTS;
        require(
            !lamps || (!receiver_light_set && !blocker_shadow_set),
            "a lamp is an emitter only: receiver_light_set and blocker_shadow_set must be NULL for lights");
        const size_t size = scene->live->read(
            [&](const stratum::Scene& s) { return lamps ? s.lights.size() : s.instances.size(); });
        const std::string what = lamps ? "lights" : "instances";
        require(static_cast<uint64_t>(first) + count <= size,
                what + " [" + std::to_string(first) + ", +" + std::to_string(count) +
                    ") are outside the scene's " + std::to_string(size));
        if (count == 0) return STRATUM_OK;
        if (lamps) {
            scene->live->edit(stratum::LiveScene::Part::Lights, [&](stratum::Scene& s) {
                for (uint32_t k = 0; k < count; ++k)
                    assign(s.lights[first + k].links, k, nullptr, nullptr, light_set_membership,
                           shadow_set_membership);
            });
            return STRATUM_OK;
        }
        for (uint32_t k = 0; k < count; ++k) {
            scene->live->edit_instance(first + k, [&](stratum::Instance& i) {
                assign(i.links, k, receiver_light_set, blocker_shadow_set, light_set_membership,
                       shadow_set_membership);
            });
        }
        return STRATUM_OK;
    });
}

}  // extern "C"
