#include "scene/vertex_normals.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace stratum {

namespace {

struct Vec3d {
    double x, y, z;
};

double dot(const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

Vec3d point(std::span<const float> xyz, size_t i) { return {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]}; }

Vec3d minus(const Vec3d& a, const Vec3d& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

Vec3d cross(const Vec3d& a, const Vec3d& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// v / |v|; a zero vector stays zero (Blender's normalize_v3).
Vec3d unit(const Vec3d& v) {
    const double length = std::sqrt(dot(v, v));
    if (!(length > 0.0)) return {0.0, 0.0, 0.0};
    const double scale = 1.0 / length;
    return {v.x * scale, v.y * scale, v.z * scale};
}

constexpr double kHalfPi = 1.5707963267948966;

// theta_c of every corner of face f, in corner order, into angles[0 .. size). The angle between
// the edges to the previous and next corners, atan2(|in x out|, -(in . out)), is the definition's
// acos(-(unit(in) . unit(out))) evaluated to a few ulps at every angle: acos of a rounded cosine
// is off by sqrt(2 u) near 0 and pi (a corner of nearly collinear edges would get a weight of
// 1e-8 instead of 0). A zero edge has no direction: theta = pi/2, as Blender's
// saacos(0) of a zero normalised edge.
void face_angles(const PolygonMeshView& m, size_t f, double* angles) {
    const size_t start = m.face_starts[f], size = m.face_sizes[f];
    const auto corner_point = [&](size_t k) { return point(m.positions, m.corner_vertices[start + k]); };
    Vec3d here = corner_point(0);
    Vec3d incoming = minus(here, corner_point(size - 1));
    for (size_t k = 0; k < size; ++k) {
        const Vec3d next = corner_point(k + 1 == size ? 0 : k + 1);
        const Vec3d outgoing = minus(next, here);
        const Vec3d normal = cross(incoming, outgoing);
        const bool zero_edge = dot(incoming, incoming) == 0.0 || dot(outgoing, outgoing) == 0.0;
        angles[k] =
            zero_edge ? kHalfPi : std::atan2(std::sqrt(dot(normal, normal)), -dot(incoming, outgoing));
        incoming = outgoing;
        here = next;
    }
}

}  // namespace

void angle_weighted_vertex_normals(const PolygonMeshView& m, std::span<float> out_normals) {
    const size_t n_face = m.face_sizes.size(), n_vert = m.positions.size() / 3;
    // Face f's angles live at angles[slot[f] ..]: a face's own range, so faces whose corner
    // ranges overlap (the ABI allows any layout) never write the same element.
    std::vector<size_t> slot(n_face + 1, 0);
    for (size_t f = 0; f < n_face; ++f) slot[f + 1] = slot[f] + m.face_sizes[f];
    std::vector<double> angles(slot[n_face]);
    // The angle per corner (an atan2) is most of the work; each face's angles depend on that face alone.
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n_face, 1024), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t f = r.begin(); f != r.end(); ++f) face_angles(m, f, angles.data() + slot[f]);
    });
    // The sums in one pass in face order, then corner order: a fixed order whatever the thread
    // count. Summing per vertex in parallel would first need each vertex's corners (a counting
    // sort over the corners: two sequential passes of this one's cost), so this pass stays serial.
    std::vector<double> sums(3 * n_vert, 0.0);
    for (size_t f = 0; f < n_face; ++f) {
        const Vec3d face_normal = point(m.face_normals, f);
        const size_t start = m.face_starts[f];
        for (size_t k = 0; k < m.face_sizes[f]; ++k) {
            const double theta = angles[slot[f] + k];
            double* sum = &sums[3 * size_t{m.corner_vertices[start + k]}];
            sum[0] += face_normal.x * theta;
            sum[1] += face_normal.y * theta;
            sum[2] += face_normal.z * theta;
        }
    }
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n_vert, 4096), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t v = r.begin(); v != r.end(); ++v) {
            const Vec3d sum{sums[3 * v], sums[3 * v + 1], sums[3 * v + 2]};
            const Vec3d n = dot(sum, sum) > 0.0 ? unit(sum) : unit(point(m.positions, v));
            out_normals[3 * v] = static_cast<float>(n.x);
            out_normals[3 * v + 1] = static_cast<float>(n.y);
            out_normals[3 * v + 2] = static_cast<float>(n.z);
        }
    });
}

}  // namespace stratum
