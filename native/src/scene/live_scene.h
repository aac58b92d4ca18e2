// A scene description that can be edited after renderers were made from it: the host's edits
// (ABI entry points) and the renderers' reads meet here, under one lock. Each edit marks the
// part of the scene it changed (per instance for instances), so a renderer can ask what changed
// since it last looked and rebuild only that (render_scene/render_scene.h).
//
// | part      | holds                                     | what a renderer redoes             |
// |-----------|-------------------------------------------|------------------------------------|
// | Meshes    | meshes (added only)                       | everything                         |
// | Textures  | textures and their bindings               | everything                         |
// | Instances | instance count and order                  | everything                         |
// | Instance i| instance i's transform, visibility, mesh  | its BVH placement, lights, bounds  |
// | Materials | materials                                 | materials, emissive lights         |
// | Lights    | lamps                                     | the light set                      |
// | World     | background colour, environment image      | the light set                      |
// | Camera    | camera                                    | nothing (read per render)          |
#pragma once

#include <cstdint>
#include <mutex>
#include <vector>

#include "scene/scene.h"

namespace stratum {

// What changed between two looks at a LiveScene.
struct SceneChanges {
    bool rebuild = false;             // meshes, textures or the instance list: build anew
    std::vector<uint32_t> instances;  // instances edited in place (indices, ascending)
    bool materials = false, lights = false, world = false, camera = false;
    bool any() const { return rebuild || !instances.empty() || materials || lights || world || camera; }
    // Both sets of changes (this one not yet applied, then `later`).
    void merge(const SceneChanges& later);
};

// Edit counters of a LiveScene: a reader keeps the ones it last synced.
struct SceneVersion {
    uint64_t structure = 0;  // meshes, textures, instance list
    std::vector<uint64_t> instances;
    uint64_t materials = 0, lights = 0, world = 0, camera = 0;
};

class LiveScene {
public:
    enum class Part { Structure, Materials, Lights, World, Camera };

    // Runs f(scene) under the lock and marks `part` changed; returns what f returns. f must not
    // change the parts it does not name (ABI entry points keep to theirs).
    template <typename F>
    auto edit(Part part, F&& f) {
        std::lock_guard lock(mutex_);
        // Marked even when f throws (a rejected value): the reader then redoes a part that did
        // not change, which costs time but never shows a stale scene.
        struct Mark {
            LiveScene* scene;
            Part part;
            ~Mark() { scene->mark(part); }
        } mark{this, part};
        return f(scene_);
    }
    // Runs f(scene.instances[index]) under the lock and marks instance `index` changed.
    template <typename F>
    auto edit_instance(uint32_t index, F&& f) {
        std::lock_guard lock(mutex_);
        ++counter_;
        version_.instances.at(index) = counter_;
        return f(scene_.instances.at(index));
    }
    // Runs f(scene) under the lock for reading.
    template <typename F>
    auto read(F&& f) const {
        std::lock_guard lock(mutex_);
        return f(static_cast<const Scene&>(scene_));
    }
    // Brings *copy up to date for a reader that last synced at *seen (a default SceneVersion:
    // never), copying only the parts that changed, and returns what changed. The meshes of
    // *copy stay where they are unless the structure changed (the reader's built scene points
    // into them).
    SceneChanges sync(Scene* copy, SceneVersion* seen) const;

private:
    void mark(Part part);

    mutable std::mutex mutex_;
    Scene scene_;
    uint64_t counter_ = 0;
    SceneVersion version_;
};

}  // namespace stratum
