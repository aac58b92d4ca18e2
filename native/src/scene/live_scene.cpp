#include "scene/live_scene.h"

#include <algorithm>

namespace stratum {

void SceneChanges::merge(const SceneChanges& later) {
    rebuild = rebuild || later.rebuild;
    std::vector<uint32_t> both;
    std::set_union(instances.begin(), instances.end(), later.instances.begin(), later.instances.end(),
                   std::back_inserter(both));
    instances = std::move(both);
    materials = materials || later.materials;
    lights = lights || later.lights;
    world = world || later.world;
    camera = camera || later.camera;
}

void LiveScene::mark(Part part) {
    ++counter_;
    switch (part) {
        case Part::Structure:
            version_.structure = counter_;
            // A changed instance list renumbers instances: each counts as changed from here on.
            version_.instances.assign(scene_.instances.size(), counter_);
            break;
        case Part::Materials:
            version_.materials = counter_;
            break;
        case Part::Lights:
            version_.lights = counter_;
            break;
        case Part::World:
            version_.world = counter_;
            break;
        case Part::Camera:
            version_.camera = counter_;
            break;
    }
}

SceneChanges LiveScene::sync(Scene* copy, SceneVersion* seen) const {
    std::lock_guard lock(mutex_);
    SceneChanges changes;
    if (seen->structure != version_.structure || seen->instances.size() != scene_.instances.size()) {
        *copy = scene_;
        *seen = version_;
        changes.rebuild = true;
        return changes;
    }
    for (uint32_t i = 0; i < scene_.instances.size(); ++i) {
        if (seen->instances[i] == version_.instances[i]) continue;
        copy->instances[i] = scene_.instances[i];
        changes.instances.push_back(i);
    }
    // A program replaced in place (stratum_scene_set_shader_program) is a materials edit; the
    // lamps that run one are rebuilt with the materials too (RenderScene::update).
    if (seen->materials != version_.materials) {
        copy->materials = scene_.materials;
        copy->programs = scene_.programs;
        changes.materials = true;
    }
    if (seen->lights != version_.lights) {
        copy->lights = scene_.lights;
        copy->light_programs = scene_.light_programs;
        changes.lights = true;
    }
    if (seen->world != version_.world) {
        copy->background = scene_.background;
        copy->environment = scene_.environment;
        changes.world = true;
    }
    if (seen->camera != version_.camera) {
        copy->camera = scene_.camera;
        changes.camera = true;
    }
    *seen = version_;
    return changes;
}

}  // namespace stratum
