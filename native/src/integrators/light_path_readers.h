// The materials, lamps and world of a scene whose node programs read Cycles' Light Path node,
// for the notices of the integrators that do not follow Cycles' camera paths (light tracing,
// radiosity): there the node gives fixed values, which the notice states.
#pragma once

#include <string>

#include "scene/scene.h"
#include "shading/light_path_state.h"

namespace stratum {

// "material 2, light 0, the world" (materials and lights by index, as the other notices name
// them); empty when no program reads the node.
inline std::string light_path_readers(const Scene& scene) {
    std::string listed;
    const auto add = [&](const std::string& name) { listed += (listed.empty() ? "" : ", ") + name; };
    std::vector<bool> material(scene.materials.size(), false);
    for (const ProgramBinding& b : scene.program_bindings)
        if (b.material_id < material.size() && reads_light_path(*scene.programs[b.program_id]))
            material[b.material_id] = true;
    for (size_t m = 0; m < material.size(); ++m)
        if (material[m]) add("material " + std::to_string(m));
    for (const LightProgram& l : scene.light_programs)
        if (reads_light_path(*scene.programs[l.program_id])) add("light " + std::to_string(l.light_id));
    if (scene.environment && scene.environment->program) add("the world");
    return listed;
}

// The notice of an integrator (`what` it does) for the programs of `scene` that read the node.
inline std::string light_path_notice(const Scene& scene, const std::string& what) {
    const std::string readers = light_path_readers(scene);
    if (readers.empty()) return {};
    return what + " does not follow Cycles' camera paths, so the Light Path node of " + readers +
           " gives fixed values: Is Camera Ray 1 and the depths 0 on surfaces the camera sees, Is Shadow Ray "
           "1 "
           "and Ray Depth 1 on surfaces a shadow ray crosses, no ray kind and the depths 0 on other "
           "surfaces, no "
           "ray kind and Ray Depth 1 on lamps and the world; choose the path integrator to render them as "
           "Cycles "
           "does";
}

}  // namespace stratum
