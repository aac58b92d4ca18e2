// Validation of the geometry the C ABI accepts (api/validation.h): meshes, their placements
// (instances) and the polygon meshes of stratum_vertex_normals.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>

#include "api/validation.h"
#include "api/validation_checks.h"
#include "scene/scene_limits.h"

namespace stratum {

using namespace abi_checks;

namespace {

// Bulk checks over a mesh's arrays (millions of values for a 1M-triangle mesh): branch-free
// loops the compiler vectorises; only when one fails does a plain loop find the first bad
// element to name it.

// True if none of the n floats is NaN or ±Inf: those are exactly the IEEE 754 binary32 values
// whose exponent bits are all ones (tested on the bits, so no floating-point mode can fold it).
bool all_finite(const float* v, size_t n) {
    uint32_t non_finite = 0;
    for (size_t i = 0; i < n; ++i) {
        uint32_t bits;
        std::memcpy(&bits, v + i, sizeof bits);
        non_finite |= static_cast<uint32_t>((bits & 0x7f800000u) == 0x7f800000u);
    }
    return non_finite == 0;
}

uint32_t max_of(const uint32_t* v, size_t n) {
    uint32_t hi = 0;
    for (size_t i = 0; i < n; ++i) hi = std::max(hi, v[i]);
    return hi;
}

// Index of the first group of `width` floats holding a non-finite value (one exists).
size_t first_non_finite(const float* v, size_t n, size_t width) {
    size_t i = 0;
    while (i < n && std::isfinite(v[i])) ++i;
    return i / width;
}

template <typename T>
void copy_into(std::vector<T>& out, const float* src, size_t count) {
    static_assert(std::is_trivially_copyable_v<T> && sizeof(T) % sizeof(float) == 0);
    out.resize(count);
    std::memcpy(static_cast<void*>(out.data()), src, count * sizeof(T));
}

}  // namespace

Mesh validate_mesh(const StratumMeshDesc& d, uint32_t material_count) {
    require(d.vertex_count > 0, "mesh vertex_count is 0");
    require(d.triangle_count > 0, "mesh triangle_count is 0");
    require(d.positions && d.triangles && d.material_ids,
            "mesh positions, triangles or material_ids is NULL");
    const size_t n_vert = d.vertex_count, n_tri = d.triangle_count;
    if (!all_finite(d.positions, 3 * n_vert)) {
        const size_t v = first_non_finite(d.positions, 3 * n_vert, 3);
        throw ValidationError("mesh vertex " + std::to_string(v) + " has a non-finite position " +
                              triple(d.positions + 3 * v));
    }
    // The largest |coordinate| (NaN excluded above): one vectorisable pass, the search for the
    // vertex to name only when it fails.
    float largest = 0.0f;
    for (size_t i = 0; i < 3 * n_vert; ++i) largest = std::max(largest, std::abs(d.positions[i]));
    if (largest > kMaxCoordinate) {
        size_t i = 0;
        while (std::abs(d.positions[i]) <= kMaxCoordinate) ++i;
        throw ValidationError("mesh vertex " + std::to_string(i / 3) + " position " +
                              triple(d.positions + 3 * (i / 3)) + " is more than " + fmt(kMaxCoordinate) +
                              " from the origin");
    }
    if (max_of(d.triangles, 3 * n_tri) >= d.vertex_count) {
        size_t i = 0;
        while (d.triangles[i] < d.vertex_count) ++i;
        throw ValidationError("mesh triangle " + std::to_string(i / 3) + " vertex index " +
                              std::to_string(d.triangles[i]) + " out of range [0, " +
                              std::to_string(d.vertex_count) + ")");
    }
    if (max_of(d.material_ids, n_tri) >= material_count) {
        size_t t = 0;
        while (d.material_ids[t] < material_count) ++t;
        throw ValidationError("mesh triangle " + std::to_string(t) + " material id " +
                              std::to_string(d.material_ids[t]) + " out of range [0, " +
                              std::to_string(material_count) + ")");
    }
    if (d.corner_normals && !all_finite(d.corner_normals, 9 * n_tri)) {
        const size_t k = first_non_finite(d.corner_normals, 9 * n_tri, 3);
        throw ValidationError("mesh corner normal " + std::to_string(k) + " is not finite " +
                              triple(d.corner_normals + 3 * k));
    }
    if (d.corner_normals && d.vertex_normals)
        throw ValidationError("mesh has both corner_normals and vertex_normals (give at most one)");
    if (d.vertex_normals && !all_finite(d.vertex_normals, 3 * n_vert)) {
        const size_t k = first_non_finite(d.vertex_normals, 3 * n_vert, 3);
        throw ValidationError("mesh vertex normal " + std::to_string(k) + " is not finite " +
                              triple(d.vertex_normals + 3 * k));
    }
    if (d.corner_uvs && !all_finite(d.corner_uvs, 6 * n_tri)) {
        const size_t k = first_non_finite(d.corner_uvs, 6 * n_tri, 2);
        throw ValidationError("mesh corner uv " + std::to_string(k) + " is not finite (" +
                              fmt(d.corner_uvs[2 * k]) + ", " + fmt(d.corner_uvs[2 * k + 1]) + ")");
    }
    if (d.corner_tangents && !all_finite(d.corner_tangents, 12 * n_tri)) {
        const size_t k = first_non_finite(d.corner_tangents, 12 * n_tri, 4);
        throw ValidationError("mesh corner tangent " + std::to_string(k) + " is not finite " +
                              triple(d.corner_tangents + 4 * k) + ", sign " +
                              fmt(d.corner_tangents[4 * k + 3]));
    }
    // All valid: one bulk copy per array.
    Mesh mesh;
    copy_into(mesh.positions, d.positions, n_vert);
    mesh.triangles.resize(n_tri);
    std::memcpy(mesh.triangles.data(), d.triangles, n_tri * sizeof(mesh.triangles[0]));
    mesh.material_ids.assign(d.material_ids, d.material_ids + n_tri);
    if (d.corner_normals) copy_into(mesh.corner_normals, d.corner_normals, 3 * n_tri);
    if (d.vertex_normals) copy_into(mesh.vertex_normals, d.vertex_normals, n_vert);
    if (d.corner_uvs) copy_into(mesh.corner_uvs, d.corner_uvs, 3 * n_tri);
    if (d.corner_tangents) {
        mesh.corner_tangents.resize(3 * n_tri);
        mesh.corner_signs.resize(3 * n_tri);
        for (size_t c = 0; c < 3 * n_tri; ++c) {
            const float* t = d.corner_tangents + 4 * c;
            mesh.corner_tangents[c] = Vec3(t[0], t[1], t[2]);
            mesh.corner_signs[c] = t[3];
        }
    }
    for (const Vec3& p : mesh.positions) {
        mesh.bounds_lo = Vec3(std::min(mesh.bounds_lo.x, p.x), std::min(mesh.bounds_lo.y, p.y),
                              std::min(mesh.bounds_lo.z, p.z));
        mesh.bounds_hi = Vec3(std::max(mesh.bounds_hi.x, p.x), std::max(mesh.bounds_hi.y, p.y),
                              std::max(mesh.bounds_hi.z, p.z));
    }
    return mesh;
}

namespace {

// The largest |world coordinate| of a mesh's bounding box placed by `m` (its 8 corners).
float placed_extent(const Mesh& mesh, const Transform& m) {
    float extent = 0.0f;
    for (int c = 0; c < 8; ++c) {
        const Vec3 corner(c & 1 ? mesh.bounds_hi.x : mesh.bounds_lo.x,
                          c & 2 ? mesh.bounds_hi.y : mesh.bounds_lo.y,
                          c & 4 ? mesh.bounds_hi.z : mesh.bounds_lo.z);
        const Vec3 w = m.point(corner);
        extent = std::max({extent, std::abs(w.x), std::abs(w.y), std::abs(w.z)});
    }
    return extent;
}

}  // namespace

uint32_t validate_pass_index(uint32_t pass_index, const std::string& what) {
    if (pass_index > STRATUM_MAX_PASS_INDEX) {
        throw ValidationError(what + " = " + std::to_string(pass_index) + " is more than " +
                              std::to_string(STRATUM_MAX_PASS_INDEX) + " (the index passes hold floats)");
    }
    return pass_index;
}

Instance validate_instance(const StratumInstanceDesc& d, const std::vector<Mesh>& meshes) {
    // Once per instance, as validate_transform: messages only on failure.
    if (d.mesh_id >= meshes.size()) {
        throw ValidationError("instance mesh_id " + std::to_string(d.mesh_id) + " out of range [0, " +
                              std::to_string(meshes.size()) + ")");
    }
    if (d.motion != 0 && d.motion != 1)
        throw ValidationError("instance motion = " + std::to_string(d.motion) + " must be 0 or 1");
    if (d.holdout != 0 && d.holdout != 1)
        throw ValidationError("instance holdout = " + std::to_string(d.holdout) + " must be 0 or 1");
    Instance inst;
    inst.mesh_id = d.mesh_id;
    inst.object_to_world = validate_transform(d.transform, "instance transform");
    inst.motion = d.motion == 1;
    inst.object_to_world_end = inst.object_to_world;
    if (inst.motion) inst.object_to_world_end = validate_transform(d.transform_end, "instance transform_end");
    // A singular or nearly singular transform is not an error here: the render scene skips such
    // a placement with a notice (scene/placement_conditioning.h), as a zero-scale object is a
    // normal modelling state. Its world extent is bounded like every coordinate. (Motion
    // interpolates between the ends affinely in scale and translation and by rotation
    // otherwise, so the ends bound every intermediate box up to the rotation's bulge of √3.)
    const Mesh& mesh = meshes[d.mesh_id];
    const float extent =
        std::max(placed_extent(mesh, inst.object_to_world), placed_extent(mesh, inst.object_to_world_end));
    if (!(extent <= kMaxCoordinate)) {
        throw ValidationError("instance transform places mesh " + std::to_string(d.mesh_id) + " up to " +
                              fmt(extent) + " from the origin, more than " + fmt(kMaxCoordinate));
    }
    inst.visibility = validate_visibility(d.visibility, "instance visibility");
    inst.holdout = d.holdout == 1;
    inst.lightgroup = validate_lightgroup(d.lightgroup, "instance lightgroup");
    inst.pass_index = validate_pass_index(d.pass_index, "instance pass_index");
    return inst;
}

PolygonMeshView validate_polygon_mesh(uint32_t vertex_count, const float* positions, uint32_t face_count,
                                      const uint32_t* face_starts, const uint32_t* face_sizes,
                                      const float* face_normals, uint32_t corner_count,
                                      const uint32_t* corner_vertices) {
    require((positions || vertex_count == 0) && (corner_vertices || corner_count == 0) &&
                ((face_starts && face_sizes && face_normals) || face_count == 0),
            "polygon mesh positions, face_starts, face_sizes, face_normals or corner_vertices is NULL");
    const size_t n_vert = vertex_count, n_face = face_count, n_corner = corner_count;
    if (n_vert && !all_finite(positions, 3 * n_vert)) {
        const size_t v = first_non_finite(positions, 3 * n_vert, 3);
        throw ValidationError("polygon mesh vertex " + std::to_string(v) + " has a non-finite position " +
                              triple(positions + 3 * v));
    }
    if (n_face && !all_finite(face_normals, 3 * n_face)) {
        const size_t f = first_non_finite(face_normals, 3 * n_face, 3);
        throw ValidationError("polygon mesh face " + std::to_string(f) + " has a non-finite normal " +
                              triple(face_normals + 3 * f));
    }
    if (n_corner && max_of(corner_vertices, n_corner) >= vertex_count) {
        size_t c = 0;
        while (corner_vertices[c] < vertex_count) ++c;
        throw ValidationError("polygon mesh corner " + std::to_string(c) + " vertex index " +
                              std::to_string(corner_vertices[c]) + " out of range [0, " +
                              std::to_string(vertex_count) + ")");
    }
    // Every face within the corners, and no more face corners in all than corners (true of any
    // layout whose faces do not overlap; it bounds the work and memory by the arrays' sizes).
    uint64_t total = 0;
    for (size_t f = 0; f < n_face; ++f) {
        const uint64_t start = face_starts[f], size = face_sizes[f];
        total += size;
        if (size == 0 || start + size > n_corner || total > n_corner) {
            throw ValidationError(
                "polygon mesh face " + std::to_string(f) + " (corners " + std::to_string(start) + " .. +" +
                std::to_string(size) + ") " +
                (size == 0 ? std::string("has no corners")
                 : start + size > n_corner
                     ? "runs past corner_count " + std::to_string(n_corner)
                     : "brings the faces' corners past corner_count " + std::to_string(n_corner)));
        }
    }
    return {std::span(positions, 3 * n_vert), std::span(face_starts, n_face), std::span(face_sizes, n_face),
            std::span(face_normals, 3 * n_face), std::span(corner_vertices, n_corner)};
}

}  // namespace stratum
