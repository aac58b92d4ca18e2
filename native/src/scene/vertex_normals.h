// Angle-weighted vertex normals of a polygon mesh, the same bits on every call and for any
// thread count (Blender < 4.1 sums them with atomic float adds from parallel tasks, so its own
// differ in their last bits from one evaluation to the next: addon export/vertex_normals.py).
//
// | input           | meaning                                                              |
// |-----------------|----------------------------------------------------------------------|
// | positions       | 3 floats per vertex                                                  |
// | face_starts     | face f's corners are corner_vertices[face_starts[f] + 0 .. size - 1] |
// | face_sizes      | corners per face (>= 1)                                              |
// | face_normals    | 3 floats per face: the host's face normals (Blender's polygon_normals) |
// | corner_vertices | the vertex of each corner                                            |
//
//   n_v = normalize( sum over the corners c of v, in face order then corner order,
//                    of N_face(c) * theta_c )
//   theta_c = acos(-(unit(e_in) . unit(e_out))),  e_in = p_c - p_prev,  e_out = p_next - p_c
//             (the corner's interior angle; theta = pi/2 where an edge is zero, as Blender's
//             saacos of a zero normalised edge), evaluated as atan2(|e_in x e_out|, -(e_in . e_out))
//
// the angle-weighted pseudo-normal (Thürmer & Wüthrich 1998, "Computing vertex normals from
// polygonal facets"), Blender 3.x's definition (mesh_normals.cc: each corner adds
// saacos(-dot(edge_prev, edge_next)) times its face normal). A vertex whose sum is zero (no
// face, or contributions that cancel) takes its position's direction, as Blender's
// normalize_v3_v3(no, co) fallback; at the origin it stays zero. Evaluated in double from the
// float inputs and rounded to float once at the end.
#pragma once

#include <cstdint>
#include <span>

namespace stratum {

struct PolygonMeshView {
    std::span<const float> positions;
    std::span<const uint32_t> face_starts;
    std::span<const uint32_t> face_sizes;
    std::span<const float> face_normals;
    std::span<const uint32_t> corner_vertices;
};

// Writes 3 floats per vertex into out_normals (size 3 x vertex count). The mesh must be valid
// (validate_polygon_mesh: every face in range, no more face corners in all than corners). Runs
// on the calling thread's TBB arena; the result does not depend on its size.
void angle_weighted_vertex_normals(const PolygonMeshView& mesh, std::span<float> out_normals);

}  // namespace stratum
