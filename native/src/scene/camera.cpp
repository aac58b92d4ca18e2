#include "scene/camera.h"

#include <algorithm>
#include <cmath>

#include "sampling/warps.h"

namespace stratum {

Vec2 sample_aperture(Vec2 u, int32_t blades, float rotation) {
    if (blades < 3) return sample_uniform_disk_concentric(u);
    const float n = static_cast<float>(blades);
    const float k = std::min(std::floor(u.x * n), n - 1.0f);
    const float u1 = std::min(u.x * n - k, 1.0f);
    // Uniform point of the triangle (0, A, B): s = sqrt(u1) scales the edge AB, u.y slides along it.
    const float half = kPi / n, centre = rotation + 2.0f * kPi * k / n;
    const float s = std::sqrt(u1);
    const float a0 = centre - half, a1 = centre + half;
    const float w0 = s * (1.0f - u.y), w1 = s * u.y;
    return {w0 * std::cos(a0) + w1 * std::cos(a1), w0 * std::sin(a0) + w1 * std::sin(a1)};
}

namespace {

// Inverse of an affine transform (3x3 by cofactors, then the translation).
Transform inverse(const Transform& t) {
    const auto& m = t.m;
    const Vec3 c0(m[0], m[4], m[8]), c1(m[1], m[5], m[9]), c2(m[2], m[6], m[10]);
    const Vec3 r0 = cross(c1, c2), r1 = cross(c2, c0), r2 = cross(c0, c1);
    const float inv_det = 1.0f / dot(c0, r0);
    Transform inv;
    const Vec3 rows[3] = {r0 * inv_det, r1 * inv_det, r2 * inv_det};
    const Vec3 tr = t.translation();
    for (int i = 0; i < 3; ++i) {
        inv.m[4 * i + 0] = rows[i].x;
        inv.m[4 * i + 1] = rows[i].y;
        inv.m[4 * i + 2] = rows[i].z;
        inv.m[4 * i + 3] = -dot(rows[i], tr);
    }
    return inv;
}

}  // namespace

Camera::Camera(const CameraParams& params, uint32_t width, uint32_t height)
    : params_(params),
      inv_width_(1.0f / static_cast<float>(width)),
      inv_height_(1.0f / static_cast<float>(height)),
      world_to_camera_(inverse(params.camera_to_world)) {
    const float w = static_cast<float>(width), h = static_cast<float>(height);
    // Blender: AUTO fits sensor_width to the larger side; VERTICAL fits sensor_height to the
    // height; HORIZONTAL fits sensor_width to the width.
    bool fit_horizontal = true;
    float sensor = params.sensor_width_mm;
    switch (params.fit) {
        case SensorFit::Auto:
            fit_horizontal = w >= h;
            break;
        case SensorFit::Horizontal:
            fit_horizontal = true;
            break;
        case SensorFit::Vertical:
            fit_horizontal = false;
            sensor = params.sensor_height_mm;
            break;
    }
    // Size of the fitted side of the view plane (at unit distance for perspective, in scene
    // units for orthographic, where ortho_scale replaces sensor/lens); shift is in units of it.
    const float fitted =
        params.type == CameraType::Orthographic ? params.ortho_scale : sensor / params.lens_mm;
    const float half_w = fit_horizontal ? 0.5f * fitted : 0.5f * fitted * w / h;
    const float half_h = fit_horizontal ? 0.5f * fitted * h / w : 0.5f * fitted;
    const float dx = params.shift_x * fitted, dy = params.shift_y * fitted;
    left_ = -half_w + dx;
    right_ = half_w + dx;
    bottom_ = -half_h + dy;
    top_ = half_h + dy;
}

CameraRay Camera::equirectangular_ray(float fx, float fy, Vec2 lens, bool through_lens) const {
    const float u = fx * inv_width_, v = fy * inv_height_;
    const float phi = (params_.longitude_min - params_.longitude_max) * u - params_.longitude_min;
    const float theta = (params_.latitude_min - params_.latitude_max) * v - params_.latitude_min + 0.5f * kPi;
    const float sin_theta = std::sin(theta);
    // Cycles' panorama space.
    Vec3 d(sin_theta * std::cos(phi), sin_theta * std::sin(phi), std::cos(theta));
    Vec3 origin(0.0f, 0.0f, 0.0f);
    if (through_lens) {
        const Vec2 a = sample_aperture(lens, params_.aperture_blades, params_.aperture_rotation);
        const Vec3 focus = d * params_.focus_distance;
        const Vec3 U = normalize(Vec3(1.0f, 0.0f, 0.0f) - d * d.x);
        const Vec3 V = normalize(cross(d, U));
        origin = U * (a.x * params_.aperture_radius) + V * (a.y * params_.aperture_radius);
        d = normalize(focus - origin);
    }
    // Panorama space to Blender camera space (blender_camera_matrix): (x, y, z) -> (−y, z, −x).
    const auto to_camera = [](Vec3 p) { return Vec3(-p.y, p.z, -p.x); };
    const Vec3 dir = normalize(params_.camera_to_world.vector(to_camera(d)));
    return {params_.camera_to_world.point(to_camera(origin)), dir, params_.clip_start, params_.clip_end};
}

CameraRay Camera::ray(float fx, float fy, Vec2 lens, bool through_lens) const {
    if (params_.type == CameraType::Equirectangular) return equirectangular_ray(fx, fy, lens, through_lens);
    const float px = left_ + (right_ - left_) * fx * inv_width_;
    const float py = bottom_ + (top_ - bottom_) * fy * inv_height_;
    // Local space: the pinhole ray goes from `origin` to `target`, one unit deeper.
    Vec3 origin(0.0f, 0.0f, 0.0f), target(px, py, -1.0f);
    if (params_.type == CameraType::Orthographic) origin = Vec3(px, py, 0.0f);
    float depth = 1.0f;
    if (through_lens) {
        // Thin lens: aim at the pinhole ray's point at depth focus_distance from a lens point.
        depth = params_.focus_distance;
        target = origin + (target - origin) * depth;
        const Vec2 a = sample_aperture(lens, params_.aperture_blades, params_.aperture_rotation);
        origin = origin + Vec3(a.x * params_.aperture_radius, a.y * params_.aperture_radius, 0.0f);
    }
    const Vec3 local = target - origin;
    // Blender clips by depth along the view axis; along the ray that is depth * |local| / local depth.
    const float inv_len = depth / length(local);
    const Vec3 dir = normalize(params_.camera_to_world.vector(local));
    return {params_.camera_to_world.point(origin), dir, params_.clip_start / inv_len,
            params_.clip_end / inv_len};
}

CameraRay Camera::generate_ray(float fx, float fy, Vec2 lens) const {
    const bool aperture = params_.aperture_radius > 0.0f;
    CameraRay r = ray(fx, fy, lens, aperture);
    // Cycles' compact ray differentials (kernel/camera/camera.h): the pinhole rays of this film
    // position and of the next pixel right and up, whatever the lens (Cycles leaves depth of
    // field out of them); their origins' and directions' differences, each the mean of the two.
    const CameraRay centre = aperture ? ray(fx, fy, lens, false) : r;
    const CameraRay right = ray(fx + 1.0f, fy, lens, false), up = ray(fx, fy + 1.0f, lens, false);
    r.dp = 0.5f * (length(right.origin - centre.origin) + length(up.origin - centre.origin));
    r.dd = 0.5f * (length(right.direction - centre.direction) + length(up.direction - centre.direction));
    return r;
}

bool Camera::connect(Vec3 x, Vec2 lens, CameraConnection* out) const {
    if (params_.type != CameraType::Perspective) return false;
    const Vec3 local_x = world_to_camera_.point(x);
    Vec3 lens_local(0.0f, 0.0f, 0.0f);
    if (params_.aperture_radius > 0.0f) {
        const Vec2 a = sample_aperture(lens, params_.aperture_blades, params_.aperture_rotation);
        lens_local = Vec3(a.x * params_.aperture_radius, a.y * params_.aperture_radius, 0.0f);
    }
    const Vec3 v = local_x - lens_local;
    const float depth = -v.z;  // the camera looks down its −Z
    // generate_ray clips by depth along the view axis (clip_start / clip_end).
    if (!(depth > params_.clip_start && depth < params_.clip_end)) return false;
    // The view-plane point at unit depth whose pinhole ray the thin-lens ray z→x follows: the
    // ray crosses the focus plane at z + v·(focus/depth), seen from the pinhole at depth focus.
    float px, py;
    if (params_.aperture_radius > 0.0f) {
        const float f = params_.focus_distance;
        px = (lens_local.x + v.x * (f / depth)) / f;
        py = (lens_local.y + v.y * (f / depth)) / f;
    } else {
        px = v.x / depth;
        py = v.y / depth;
    }
    const float local_length = length(v);
    const float cos_theta = depth / local_length;
    out->lens_point = params_.camera_to_world.point(lens_local);
    const Vec3 to = out->lens_point - x;
    out->distance = length(to);
    if (!(out->distance > 0.0f)) return false;
    out->to_camera = to / out->distance;
    out->unclipped = out->distance * (1.0f - params_.clip_start / depth);
    out->film = {(px - left_) / (right_ - left_) / inv_width_,
                 (py - bottom_) / (top_ - bottom_) / inv_height_};
    const float pixel_area = (right_ - left_) * (top_ - bottom_) * inv_width_ * inv_height_;
    out->importance = 1.0f / (out->distance * out->distance * pixel_area * cos_theta * cos_theta * cos_theta);
    return true;
}

float Camera::z_depth(Vec3 x) const {
    const Vec3 offset = x - params_.camera_to_world.translation();
    if (params_.type == CameraType::Equirectangular) return length(offset);
    return to_view_space(offset).z;
}

float Camera::distance(Vec3 x) const {
    if (params_.type == CameraType::Orthographic) return std::fabs(z_depth(x));
    return length(x - params_.camera_to_world.translation());
}

Vec3 Camera::to_view_space(Vec3 direction) const {
    const Transform& m = params_.camera_to_world;
    return {dot(direction, normalize(m.column(0))), dot(direction, normalize(m.column(1))),
            -dot(direction, normalize(m.column(2)))};
}

}  // namespace stratum
