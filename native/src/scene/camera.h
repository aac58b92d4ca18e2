// Blender's perspective camera: lens, sensor size and fit, shift and clipping, computed as
// Blender's BKE_camera_params_compute_viewplane does, so Stratum frames exactly what Cycles frames.
//
// | parameter         | meaning (Blender name) |
// |-------------------|------------------------|
// | lens_mm           | focal length (lens) |
// | sensor_*_mm       | sensor_width / sensor_height |
// | fit               | sensor_fit: AUTO uses sensor_width along the larger image side |
// | shift_x/y         | lens shift, in units of the fitted image side |
// | clip_start/end    | ray extent along the view direction |
#pragma once

#include <cstdint>

#include "core/math.h"

namespace stratum {

enum class SensorFit : int32_t { Auto = 0, Horizontal = 1, Vertical = 2 };

struct CameraParams {
    float lens_mm = 50.0f;
    float sensor_width_mm = 36.0f;
    float sensor_height_mm = 24.0f;
    SensorFit fit = SensorFit::Auto;
    float shift_x = 0.0f, shift_y = 0.0f;
    float clip_start = 0.1f, clip_end = 1000.0f;
    Transform camera_to_world;
};

struct CameraRay {
    Vec3 origin;
    Vec3 direction;  // unit length
    float t_min, t_max;
};

class Camera {
public:
    Camera(const CameraParams& params, uint32_t width, uint32_t height);
    // Ray through the film position (fx, fy) in pixels: (0,0) is the bottom-left corner of the
    // image, (width, height) the top-right, as Blender's render result rows run bottom to top.
    CameraRay generate_ray(float fx, float fy) const;
    // The view plane at unit distance in front of the camera: [left,right] x [bottom,top].
    float left() const { return left_; }
    float right() const { return right_; }
    float bottom() const { return bottom_; }
    float top() const { return top_; }

private:
    CameraParams params_;
    float inv_width_, inv_height_;
    float left_, right_, bottom_, top_;
};

}  // namespace stratum
