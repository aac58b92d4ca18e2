// C entry point for vertex normals without a scene (stratum_vertex_normals): the add-on computes
// a smooth mesh's normals here in Blender < 4.1, whose own vary between evaluations. Every input
// is validated and every exception stops here (api/abi_guard.h).
#include <tbb/task_arena.h>

#include <string>

#include "api/abi_guard.h"
#include "scene/vertex_normals.h"
#include "stratum/stratum.h"

namespace {

// The render setting "threads"' limit (setting_registry.cpp): a task arena reserves its slots.
constexpr uint32_t kMaxThreads = 1024;

}  // namespace

StratumStatus stratum_vertex_normals(uint32_t vertex_count, const float* positions, uint32_t face_count,
                                     const uint32_t* face_starts, const uint32_t* face_sizes,
                                     const float* face_normals, uint32_t corner_count,
                                     const uint32_t* corner_vertices, uint32_t threads, float* out_normals) {
    using stratum::require;
    return stratum::abi::guarded("stratum_vertex_normals", [&] {
        require(out_normals || vertex_count == 0, "out_normals is NULL");
        require(threads <= kMaxThreads, "threads = " + std::to_string(threads) + " out of range [0, " +
                                            std::to_string(kMaxThreads) + "]");
        const stratum::PolygonMeshView mesh =
            stratum::validate_polygon_mesh(vertex_count, positions, face_count, face_starts, face_sizes,
                                           face_normals, corner_count, corner_vertices);
        tbb::task_arena arena(threads == 0 ? tbb::task_arena::automatic : static_cast<int>(threads));
        arena.execute([&] {
            stratum::angle_weighted_vertex_normals(mesh, std::span(out_normals, 3 * size_t{vertex_count}));
        });
        return STRATUM_OK;
    });
}
