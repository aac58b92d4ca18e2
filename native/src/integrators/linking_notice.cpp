#include "integrators/linking_notice.h"

#include "render_scene/render_scene.h"

namespace stratum {

namespace {

bool links_as_emitter(const LightLinks& links) {
    return links.light_set_membership != kAllLinkSets || links.shadow_set_membership != kAllLinkSets;
}

}  // namespace

std::optional<std::string> unsupported_linking_notice(const Scene& scene, const std::string& method) {
    std::string listed;
    const auto list = [&listed](const std::string& what) { listed += (listed.empty() ? "" : ", ") + what; };
    for (size_t i = 0; i < scene.lights.size(); ++i)
        if (links_as_emitter(scene.lights[i].links)) list("light " + std::to_string(i));
    for (size_t i = 0; i < scene.instances.size(); ++i) {
        const Instance& inst = scene.instances[i];
        if (!links_as_emitter(inst.links)) continue;
        bool emits = false;
        for (const uint32_t m : scene.meshes[inst.mesh_id].material_ids)
            emits = emits || !material_emission(scene.materials[m]).is_black();
        if (emits) list("the emission of instance " + std::to_string(i));
    }
    if (listed.empty()) return std::nullopt;
    return method + " ignores light and shadow linking: " + listed +
           " light every surface and are shadowed by every occluder (render with the path tracer to link "
           "them)";
}

}  // namespace stratum
