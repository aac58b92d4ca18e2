// The C entry points of stratum/scene.h (texture_api.cpp has the textures'): building a scene,
// editing it live, saving and loading it, measuring its ray throughput. Every input is
// validated here and every exception stops here (api/abi_guard.h).
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "api/abi_guard.h"
#include "api/scene_file.h"
#include "api/scene_handle.h"
#include "api/validation.h"
#include "render/ray_throughput.h"
#include "scene/scene.h"
#include "stratum/stratum.h"

namespace {

using stratum::require;
using stratum::abi::fail;
using stratum::abi::guarded;

// Replaces material `id` with `m` (checked to exist under the lock).
void replace_material(StratumScene* scene, uint32_t id, stratum::SceneMaterial m) {
    scene->live->edit(stratum::LiveScene::Part::Materials, [&](stratum::Scene& s) {
        require(id < s.materials.size(), "material " + std::to_string(id) +
                                             " does not exist (the scene has " +
                                             std::to_string(s.materials.size()) + ")");
        // A closure edit keeps the material's pass index (its own edit below).
        s.materials[id].closures = std::move(m.closures);
    });
}

}  // namespace

extern "C" {

StratumStatus stratum_scene_create(StratumScene** out_scene) {
    return guarded("stratum_scene_create", [&] {
        require(out_scene != nullptr, "out_scene is NULL");
        *out_scene = new StratumScene();
        return STRATUM_OK;
    });
}

void stratum_scene_destroy(StratumScene* scene) { delete scene; }

StratumStatus stratum_scene_add_material(StratumScene* scene, const StratumMaterialDesc* material,
                                         uint32_t* out_id) {
    return guarded("stratum_scene_add_material", [&] {
        require(scene && material, "scene or material is NULL");
        stratum::SceneMaterial m{
            {stratum::WeightedClosure{stratum::Rgb(1.0f), stratum::validate_material(*material)}}};
        const uint32_t id = scene->live->edit(stratum::LiveScene::Part::Materials, [&](stratum::Scene& s) {
            s.materials.push_back(std::move(m));
            return static_cast<uint32_t>(s.materials.size() - 1);
        });
        if (out_id) *out_id = id;
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_add_closure_material(StratumScene* scene, const StratumClosureDesc* closures,
                                                 uint32_t closure_count, uint32_t* out_id) {
    return guarded("stratum_scene_add_closure_material", [&] {
        require(scene, "scene is NULL");
        stratum::SceneMaterial m = stratum::validate_closure_material(closures, closure_count);
        const uint32_t id = scene->live->edit(stratum::LiveScene::Part::Materials, [&](stratum::Scene& s) {
            s.materials.push_back(std::move(m));
            return static_cast<uint32_t>(s.materials.size() - 1);
        });
        if (out_id) *out_id = id;
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_add_mesh(StratumScene* scene, const StratumMeshDesc* mesh, uint32_t* out_id) {
    return guarded("stratum_scene_add_mesh", [&] {
        require(scene && mesh, "scene or mesh is NULL");
        const uint32_t id = scene->live->edit(stratum::LiveScene::Part::Structure, [&](stratum::Scene& s) {
            s.meshes.push_back(stratum::validate_mesh(*mesh, static_cast<uint32_t>(s.materials.size())));
            return static_cast<uint32_t>(s.meshes.size() - 1);
        });
        if (out_id) *out_id = id;
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_add_instance(StratumScene* scene, uint32_t mesh_id, const float transform[16]) {
    return guarded("stratum_scene_add_instance", [&] {
        require(scene && transform, "scene or transform is NULL");
        // A static instance seen by every ray: the _ex description with those values.
        StratumInstanceDesc d{};
        d.mesh_id = mesh_id;
        std::copy(transform, transform + 16, d.transform);
        d.visibility = STRATUM_VISIBLE_ALL;
        scene->live->edit(stratum::LiveScene::Part::Structure, [&](stratum::Scene& s) {
            s.instances.push_back(stratum::validate_instance(d, s.meshes));
        });
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_add_instances(StratumScene* scene, uint32_t count, const uint32_t* mesh_ids,
                                          const float* transforms, uint32_t* out_failed_index) {
    if (out_failed_index) *out_failed_index = UINT32_MAX;
    return guarded("stratum_scene_add_instances", [&] {
        require(scene, "scene is NULL");
        if (count == 0) return STRATUM_OK;
        require(mesh_ids && transforms, "mesh_ids or transforms is NULL");
        // Every instance is validated before any is added (all or nothing), under one lock and
        // with one structure mark: one add_instance per row marks every instance placed so far
        // as changed, O(n^2) over a batch.
        scene->live->edit(stratum::LiveScene::Part::Structure, [&](stratum::Scene& s) {
            std::vector<stratum::Instance> added;
            added.reserve(count);
            StratumInstanceDesc d{};
            d.visibility = STRATUM_VISIBLE_ALL;
            for (uint32_t i = 0; i < count; ++i) {
                d.mesh_id = mesh_ids[i];
                std::copy(transforms + 16 * size_t{i}, transforms + 16 * (size_t{i} + 1), d.transform);
                try {
                    added.push_back(stratum::validate_instance(d, s.meshes));
                } catch (const stratum::ValidationError&) {
                    if (out_failed_index) *out_failed_index = i;
                    throw;
                }
            }
            s.instances.insert(s.instances.end(), added.begin(), added.end());
        });
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_add_instance_ex(StratumScene* scene, const StratumInstanceDesc* instance) {
    return guarded("stratum_scene_add_instance_ex", [&] {
        require(scene && instance, "scene or instance is NULL");
        scene->live->edit(stratum::LiveScene::Part::Structure, [&](stratum::Scene& s) {
            s.instances.push_back(stratum::validate_instance(*instance, s.meshes));
        });
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_add_light(StratumScene* scene, const StratumLightDesc* light) {
    return guarded("stratum_scene_add_light", [&] {
        require(scene && light, "scene or light is NULL");
        stratum::LightParams l = stratum::validate_light(*light);
        scene->live->edit(stratum::LiveScene::Part::Lights,
                          [&](stratum::Scene& s) { s.lights.push_back(l); });
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_set_camera(StratumScene* scene, const StratumCameraDesc* camera) {
    return guarded("stratum_scene_set_camera", [&] {
        require(scene && camera, "scene or camera is NULL");
        stratum::CameraParams c = stratum::validate_camera(*camera);
        scene->live->edit(stratum::LiveScene::Part::Camera, [&](stratum::Scene& s) { s.camera = c; });
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_set_background(StratumScene* scene, const float rgb[3]) {
    return guarded("stratum_scene_set_background", [&] {
        require(scene && rgb, "scene or rgb is NULL");
        const stratum::Rgb background = stratum::validate_radiance(rgb, "background");
        scene->live->edit(stratum::LiveScene::Part::World,
                          [&](stratum::Scene& s) { s.background = background; });
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_set_world_lightgroup(StratumScene* scene, uint32_t lightgroup) {
    return guarded("stratum_scene_set_world_lightgroup", [&] {
        require(scene != nullptr, "scene is NULL");
        const uint32_t group = stratum::validate_lightgroup(lightgroup, "world lightgroup");
        scene->live->edit(stratum::LiveScene::Part::World,
                          [&](stratum::Scene& s) { s.world_lightgroup = group; });
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_set_environment(StratumScene* scene, const float* rgb, uint32_t width,
                                            uint32_t height, float strength, const float rotation[9]) {
    return guarded("stratum_scene_set_environment", [&] {
        require(scene != nullptr, "scene is NULL");
        stratum::Environment e = stratum::validate_environment(rgb, width, height, strength, rotation);
        scene->live->edit(stratum::LiveScene::Part::World,
                          [&](stratum::Scene& s) { s.environment = std::move(e); });
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_set_instance(StratumScene* scene, uint32_t index,
                                         const StratumInstanceDesc* instance) {
    return guarded("stratum_scene_set_instance", [&] {
        require(scene && instance, "scene or instance is NULL");
        const stratum::Instance validated = scene->live->read([&](const stratum::Scene& s) {
            require(index < s.instances.size(), "instance " + std::to_string(index) +
                                                    " does not exist (the scene has " +
                                                    std::to_string(s.instances.size()) + ")");
            return stratum::validate_instance(*instance, s.meshes);
        });
        scene->live->edit_instance(index, [&](stratum::Instance& i) {
            // Object Info's values and the linking sets are set apart
            // (stratum_scene_set_instance_object_info, stratum_scene_set_light_linking).
            const float random = i.random, alpha = i.alpha;
            const stratum::Rgb color = i.color;
            const stratum::LightLinks links = i.links;
            i = validated;
            i.random = random;
            i.color = color;
            i.alpha = alpha;
            i.links = links;
        });
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_set_instance_object_info(StratumScene* scene, uint32_t first, uint32_t count,
                                                     const float* random, const float* color) {
    return guarded("stratum_scene_set_instance_object_info", [&] {
        require(scene != nullptr, "scene is NULL");
        for (uint32_t k = 0; random && k < count; ++k)
            require(
                random[k] >= 0.0f && random[k] <= 1.0f,
                "random[" + std::to_string(k) + "] = " + std::to_string(random[k]) + " is outside [0, 1]");
        for (uint64_t k = 0; color && k < 4ull * count; ++k)
            require(std::isfinite(color[k]),
                    "color[" + std::to_string(k) + "] = " + std::to_string(color[k]) + " is not finite");
        const size_t instances =
            scene->live->read([](const stratum::Scene& s) { return s.instances.size(); });
        require(static_cast<uint64_t>(first) + count <= instances,
                "instances [" + std::to_string(first) + ", +" + std::to_string(count) +
                    ") are outside the scene's " + std::to_string(instances));
        for (uint32_t k = 0; k < count; ++k) {
            scene->live->edit_instance(first + k, [&](stratum::Instance& i) {
                if (random) i.random = random[k];
                if (color) {
                    i.color = stratum::Rgb(color[4 * k], color[4 * k + 1], color[4 * k + 2]);
                    i.alpha = color[4 * k + 3];
                }
            });
        }
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_set_material(StratumScene* scene, uint32_t material_id,
                                         const StratumMaterialDesc* material) {
    return guarded("stratum_scene_set_material", [&] {
        require(scene && material, "scene or material is NULL");
        replace_material(
            scene, material_id,
            {{stratum::WeightedClosure{stratum::Rgb(1.0f), stratum::validate_material(*material)}}});
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_set_closure_material(StratumScene* scene, uint32_t material_id,
                                                 const StratumClosureDesc* closures, uint32_t closure_count) {
    return guarded("stratum_scene_set_closure_material", [&] {
        require(scene, "scene is NULL");
        replace_material(scene, material_id, stratum::validate_closure_material(closures, closure_count));
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_set_material_pass_index(StratumScene* scene, uint32_t material_id,
                                                    uint32_t pass_index) {
    return guarded("stratum_scene_set_material_pass_index", [&] {
        require(scene, "scene is NULL");
        const uint32_t index = stratum::validate_pass_index(pass_index, "material pass_index");
        scene->live->edit(stratum::LiveScene::Part::Materials, [&](stratum::Scene& s) {
            require(material_id < s.materials.size(), "material " + std::to_string(material_id) +
                                                          " does not exist (the scene has " +
                                                          std::to_string(s.materials.size()) + ")");
            s.materials[material_id].pass_index = index;
        });
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_set_light(StratumScene* scene, uint32_t index, const StratumLightDesc* light) {
    return guarded("stratum_scene_set_light", [&] {
        require(scene && light, "scene or light is NULL");
        const stratum::LightParams l = stratum::validate_light(*light);
        scene->live->edit(stratum::LiveScene::Part::Lights, [&](stratum::Scene& s) {
            require(index < s.lights.size(), "light " + std::to_string(index) +
                                                 " does not exist (the scene has " +
                                                 std::to_string(s.lights.size()) + ")");
            // The linking sets are set apart (stratum_scene_set_light_linking).
            const stratum::LightLinks links = s.lights[index].links;
            s.lights[index] = l;
            s.lights[index].links = links;
        });
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_save(const StratumScene* scene, const char* path) {
    return guarded("stratum_scene_save", [&] {
        require(scene && path, "scene or path is NULL");
        const std::string error =
            scene->live->read([&](const stratum::Scene& s) { return stratum::save_scene_file(s, path); });
        return error.empty() ? STRATUM_OK : fail(STRATUM_ERROR_IO, "stratum_scene_save: " + error);
    });
}

StratumStatus stratum_scene_load(const char* path, StratumScene** out_scene) {
    return guarded("stratum_scene_load", [&] {
        require(path && out_scene, "path or out_scene is NULL");
        *out_scene = nullptr;
        auto scene = std::make_unique<StratumScene>();
        std::string error;
        const StratumStatus status = stratum::load_scene_file(path, scene.get(), &error);
        if (status != STRATUM_OK)
            return fail(status, "stratum_scene_load: " + std::string(path) + ": " + error);
        *out_scene = scene.release();
        return STRATUM_OK;
    });
}

StratumStatus stratum_scene_measure_ray_throughput(const StratumScene* scene, uint32_t width, uint32_t height,
                                                   uint32_t samples, uint32_t max_bounces, uint32_t threads,
                                                   double* out_rays, double* out_seconds) {
    return guarded("stratum_scene_measure_ray_throughput", [&] {
        require(scene && out_rays && out_seconds, "scene, out_rays or out_seconds is NULL");
        require(width > 0 && height > 0 && width <= 65536 && height <= 65536,
                "resolution " + std::to_string(width) + "x" + std::to_string(height) +
                    " out of range [1, 65536]");
        require(samples > 0 && samples <= (1u << 16),
                "samples = " + std::to_string(samples) + " out of range [1, 65536]");
        require(max_bounces <= 1024,
                "max_bounces = " + std::to_string(max_bounces) + " out of range [0, 1024]");
        const stratum::RayThroughput t = scene->live->read([&](const stratum::Scene& s) {
            return stratum::measure_ray_throughput(s, width, height, samples, max_bounces, threads);
        });
        *out_rays = t.rays;
        *out_seconds = t.seconds;
        return STRATUM_OK;
    });
}

}  // extern "C"
