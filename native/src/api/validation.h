// Validation of every value the C ABI accepts. Each function converts a C description into
// the core's type or throws ValidationError with a message that names the bad value.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

#include "bsdf/closure_set.h"
#include "film/film.h"
#include "scene/scene.h"
#include "scene/vertex_normals.h"
#include "stratum/stratum.h"

namespace stratum {

class ValidationError : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

// Throws ValidationError(message) unless `condition` holds: every validator's check, and the C
// entry points' (api/abi_guard.h turns the exception into STRATUM_ERROR_INVALID_ARGUMENT). Build
// the message only on failure in per-element loops: composing it eagerly cost seconds on a
// 200k-triangle mesh.
inline void require(bool condition, const std::string& message) {
    if (!condition) throw ValidationError(message);
}

Material validate_material(const StratumMaterialDesc& desc);
// A closure material: 1..kMaxClosures closures, weights finite and >= 0.
SceneMaterial validate_closure_material(const StratumClosureDesc* closures, uint32_t count);
Mesh validate_mesh(const StratumMeshDesc& desc, uint32_t material_count);
// Ray-visibility bits (STRATUM_VISIBLE_*) of an instance or a light; `what` names them.
uint32_t validate_visibility(uint32_t bits, const char* what);
// A light group (0 none, 1..STRATUM_MAX_LIGHT_GROUPS); `what` names it.
uint32_t validate_lightgroup(uint32_t group, const char* what);
// meshes: the scene's meshes (mesh_id must index one; its bounds limit the placement).
// An object's or material's pass index (the IndexOB / IndexMA passes); `what` names it.
uint32_t validate_pass_index(uint32_t pass_index, const std::string& what);
Instance validate_instance(const StratumInstanceDesc& desc, const std::vector<Mesh>& meshes);
LightParams validate_light(const StratumLightDesc& desc);
CameraParams validate_camera(const StratumCameraDesc& desc);
Transform validate_transform(const float* m, const char* what);
Rgb validate_radiance(const float* rgb, const char* what);
// A film made from the bytes of stratum_renderer_read_sums (header, sizes and passes checked).
std::unique_ptr<Film> validate_film_sums(const void* bytes, size_t size);
// The arrays of stratum_vertex_normals as spans, each checked (stratum.h: finite floats, corner
// vertices in range, faces of >= 1 corner within corner_count and at most corner_count corners in all).
PolygonMeshView validate_polygon_mesh(uint32_t vertex_count, const float* positions, uint32_t face_count,
                                      const uint32_t* face_starts, const uint32_t* face_sizes,
                                      const float* face_normals, uint32_t corner_count,
                                      const uint32_t* corner_vertices);
Environment validate_environment(const float* rgb, uint32_t width, uint32_t height, float strength,
                                 const float* rotation);

}  // namespace stratum
