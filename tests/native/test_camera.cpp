// The camera frames exactly what Blender frames (BKE_camera_params_compute_viewplane):
// the fitted sensor side spans sensor/lens at unit distance, shift moves the view plane by
// shift × that span, clipping is by depth.
#include <gtest/gtest.h>

#include "scene/camera.h"

using namespace stratum;

namespace {

CameraParams params(float lens, float sw, float sh, SensorFit fit, float shift_x = 0, float shift_y = 0) {
    CameraParams p;
    p.lens_mm = lens;
    p.sensor_width_mm = sw;
    p.sensor_height_mm = sh;
    p.fit = fit;
    p.shift_x = shift_x;
    p.shift_y = shift_y;
    return p;
}

}  // namespace

TEST(Camera, AutoFitUsesSensorWidthAlongTheLargerSide) {
    // Landscape 64x32, 50 mm lens, 36 mm sensor: half width 18/50.
    const Camera wide(params(50, 36, 24, SensorFit::Auto), 64, 32);
    EXPECT_FLOAT_EQ(wide.right(), 0.36f);
    EXPECT_FLOAT_EQ(wide.top(), 0.18f);
    // Portrait 32x64: AUTO puts sensor_width along the height.
    const Camera tall(params(50, 36, 24, SensorFit::Auto), 32, 64);
    EXPECT_FLOAT_EQ(tall.top(), 0.36f);
    EXPECT_FLOAT_EQ(tall.right(), 0.18f);
}

TEST(Camera, VerticalFitUsesSensorHeight) {
    const Camera c(params(50, 36, 24, SensorFit::Vertical), 64, 32);
    EXPECT_FLOAT_EQ(c.top(), 0.24f);
    EXPECT_FLOAT_EQ(c.right(), 0.48f);
    const Camera h(params(50, 36, 24, SensorFit::Horizontal), 32, 64);
    EXPECT_FLOAT_EQ(h.right(), 0.36f);
    EXPECT_FLOAT_EQ(h.top(), 0.72f);
}

TEST(Camera, ShiftIsInUnitsOfTheFittedSide) {
    const Camera c(params(50, 36, 24, SensorFit::Auto, 0.25f, -0.5f), 64, 32);
    EXPECT_FLOAT_EQ(c.left(), -0.36f + 0.18f);
    EXPECT_FLOAT_EQ(c.right(), 0.36f + 0.18f);
    EXPECT_FLOAT_EQ(c.bottom(), -0.18f - 0.36f);
}

TEST(Camera, RaysGoThroughTheViewPlaneAndClipByDepth) {
    CameraParams p = params(50, 36, 24, SensorFit::Auto);
    p.clip_start = 0.5f;
    p.clip_end = 10.0f;
    const Camera c(p, 64, 32);
    const CameraRay centre = c.generate_ray(32, 16);
    EXPECT_NEAR(centre.direction.z, -1.0f, 1e-6f);
    EXPECT_FLOAT_EQ(centre.t_min, 0.5f);
    const CameraRay corner = c.generate_ray(64, 32);  // top-right corner
    EXPECT_NEAR(corner.direction.x / -corner.direction.z, 0.36f, 1e-6f);
    EXPECT_NEAR(corner.direction.y / -corner.direction.z, 0.18f, 1e-6f);
    // Depth clip: t * cos(angle to the axis) = clip distance.
    EXPECT_NEAR(corner.t_min * -corner.direction.z, 0.5f, 1e-6f);
    EXPECT_NEAR(corner.t_max * -corner.direction.z, 10.0f, 1e-5f);
}
