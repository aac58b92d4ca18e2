#include "scene/camera.h"

namespace stratum {

Camera::Camera(const CameraParams& params, uint32_t width, uint32_t height)
    : params_(params),
      inv_width_(1.0f / static_cast<float>(width)),
      inv_height_(1.0f / static_cast<float>(height)) {
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
    // Size of the fitted side of the view plane at unit distance; shift is in units of it.
    const float fitted = sensor / params.lens_mm;
    const float half_w = fit_horizontal ? 0.5f * fitted : 0.5f * fitted * w / h;
    const float half_h = fit_horizontal ? 0.5f * fitted * h / w : 0.5f * fitted;
    const float dx = params.shift_x * fitted, dy = params.shift_y * fitted;
    left_ = -half_w + dx;
    right_ = half_w + dx;
    bottom_ = -half_h + dy;
    top_ = half_h + dy;
}

CameraRay Camera::generate_ray(float fx, float fy) const {
    const float px = left_ + (right_ - left_) * fx * inv_width_;
    const float py = bottom_ + (top_ - bottom_) * fy * inv_height_;
    const Vec3 local(px, py, -1.0f);
    const float inv_len = 1.0f / length(local);
    // Blender clips by depth along the view axis; along the ray that is depth / cos = depth*|local|.
    const Vec3 dir = normalize(params_.camera_to_world.vector(local));
    return {params_.camera_to_world.translation(), dir, params_.clip_start / inv_len,
            params_.clip_end / inv_len};
}

}  // namespace stratum
