// The camera frames exactly what Blender frames (BKE_camera_params_compute_viewplane):
// the fitted sensor side spans sensor/lens at unit distance, shift moves the view plane by
// shift × that span, clipping is by depth.
#include <gtest/gtest.h>
#include <stratum/stratum.h>

#include <cstdio>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "chi_square.h"
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

// ---- orthographic --------------------------------------------------------------------------

namespace {

CameraParams ortho(float scale, SensorFit fit, float shift_x = 0, float shift_y = 0) {
    CameraParams p = params(50, 36, 24, fit, shift_x, shift_y);
    p.type = CameraType::Orthographic;
    p.ortho_scale = scale;
    return p;
}

// Camera at (1, 2, 3) looking down world +Y (Blender's rotation (90, 0, 0)): local x -> x,
// local y -> z, local -z -> +y.
Transform looking_along_y() {
    const float m[16] = {1, 0, 0, 1, 0, 0, -1, 2, 0, 1, 0, 3, 0, 0, 0, 1};
    return Transform::from_row_major(m);
}

}  // namespace

TEST(Camera, OrthographicViewRectangleIsOrthoScaleWithFitAndShift) {
    // Landscape 64x32, AUTO: the width spans ortho_scale 4.
    const Camera wide(ortho(4, SensorFit::Auto), 64, 32);
    EXPECT_FLOAT_EQ(wide.right(), 2.0f);
    EXPECT_FLOAT_EQ(wide.top(), 1.0f);
    // Portrait, AUTO: the height spans it.
    const Camera tall(ortho(4, SensorFit::Auto), 32, 64);
    EXPECT_FLOAT_EQ(tall.top(), 2.0f);
    EXPECT_FLOAT_EQ(tall.right(), 1.0f);
    // VERTICAL on a landscape image: the height spans it; sensor sizes play no part.
    const Camera vertical(ortho(4, SensorFit::Vertical), 64, 32);
    EXPECT_FLOAT_EQ(vertical.top(), 2.0f);
    EXPECT_FLOAT_EQ(vertical.right(), 4.0f);
    // Shift in units of ortho_scale.
    const Camera shifted(ortho(4, SensorFit::Auto, 0.25f, -0.5f), 64, 32);
    EXPECT_FLOAT_EQ(shifted.left(), -2.0f + 1.0f);
    EXPECT_FLOAT_EQ(shifted.right(), 2.0f + 1.0f);
    EXPECT_FLOAT_EQ(shifted.bottom(), -1.0f - 2.0f);
    EXPECT_FLOAT_EQ(shifted.top(), 1.0f - 2.0f);
}

TEST(Camera, OrthographicRaysAreParallelFromTheViewRectangleAndClipByDepth) {
    CameraParams p = ortho(4, SensorFit::Auto, 0.25f, 0.0f);
    p.clip_start = 0.5f;
    p.clip_end = 10.0f;
    p.camera_to_world = looking_along_y();
    const Camera c(p, 64, 32);
    for (const auto& [fx, fy] : std::vector<std::pair<float, float>>{{0, 0}, {64, 32}, {32, 16}, {10, 27}}) {
        const CameraRay r = c.generate_ray(fx, fy);
        EXPECT_NEAR(r.direction.x, 0.0f, 1e-6f);
        EXPECT_NEAR(r.direction.y, 1.0f, 1e-6f);
        EXPECT_NEAR(r.direction.z, 0.0f, 1e-6f);
        // Origin on the view rectangle (x: [-1, 3], local y -> world z: [-1, 1]) through the camera.
        EXPECT_NEAR(r.origin.x, 1.0f + (-1.0f + 4.0f * fx / 64), 1e-5f);
        EXPECT_NEAR(r.origin.y, 2.0f, 1e-6f);
        EXPECT_NEAR(r.origin.z, 3.0f + (-1.0f + 2.0f * fy / 32), 1e-5f);
        EXPECT_FLOAT_EQ(r.t_min, 0.5f);
        EXPECT_FLOAT_EQ(r.t_max, 10.0f);
    }
}

// ---- thin lens ------------------------------------------------------------------------------

TEST(Camera, ThinLensRaysThroughAPixelMeetOnTheFocalPlane) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> uni(0.0f, 1.0f);
    for (const CameraType type : {CameraType::Perspective, CameraType::Orthographic}) {
        for (const int blades : {0, 5}) {
            CameraParams p = type == CameraType::Perspective ? params(50, 36, 24, SensorFit::Auto, 0.1f, 0.0f)
                                                             : ortho(4, SensorFit::Auto, 0.1f, 0.0f);
            p.clip_start = 0.5f;
            p.clip_end = 100.0f;
            p.camera_to_world = looking_along_y();
            const Camera pinhole(p, 64, 32);
            p.aperture_radius = 0.3f;
            p.focus_distance = 7.0f;
            p.aperture_blades = blades;
            p.aperture_rotation = 0.4f;
            const Camera lens(p, 64, 32);
            for (int pixel = 0; pixel < 8; ++pixel) {
                const float fx = 64 * uni(rng), fy = 32 * uni(rng);
                const CameraRay r0 = pinhole.generate_ray(fx, fy);
                // The pinhole ray at depth 7 (depth = world y - 2 here).
                const Vec3 focus = r0.origin + r0.direction * (7.0f / r0.direction.y);
                float spread = 0.0f;
                for (int k = 0; k < 64; ++k) {
                    const CameraRay r = lens.generate_ray(fx, fy, {uni(rng), uni(rng)});
                    EXPECT_NEAR(length(r.direction), 1.0f, 1e-5f);
                    // The lens point lies on the pinhole's z = 0 plane, within the aperture.
                    EXPECT_NEAR(r.origin.y, 2.0f, 1e-5f);
                    EXPECT_LE(length(r.origin - r0.origin), 0.3f + 1e-5f);
                    spread = std::max(spread, length(r.origin - r0.origin));
                    const Vec3 hit = r.origin + r.direction * (7.0f / r.direction.y);
                    EXPECT_NEAR(length(hit - focus), 0.0f, 2e-5f * 7.0f);
                    // Clipped by depth: the extent's ends lie at depths 0.5 and 100.
                    EXPECT_NEAR(r.t_min * r.direction.y, 0.5f, 1e-5f);
                    EXPECT_NEAR(r.t_max * r.direction.y, 100.0f, 1e-3f);
                }
                EXPECT_GT(spread, 0.15f);  // the lens is really used
            }
        }
    }
}

namespace {

// Inside the unit disk (blades 0) or the regular n-gon inscribed in it with vertices at
// rotation + (2k+1) pi/n, i.e. with edge normals at rotation + 2 pi k / n and apothem cos(pi/n).
bool inside_aperture(double x, double y, int blades, double rotation) {
    if (blades == 0) return x * x + y * y <= 1.0;
    for (int k = 0; k < blades; ++k) {
        const double a = rotation + 2.0 * M_PI * k / blades;
        if (x * std::cos(a) + y * std::sin(a) > std::cos(M_PI / blades)) return false;
    }
    return true;
}

double aperture_area(int blades) { return blades == 0 ? M_PI : 0.5 * blades * std::sin(2.0 * M_PI / blades); }

}  // namespace

// Uniform over the aperture: every point inside, and the counts in a 16x16 grid over [-1,1]^2
// match N x (area of cell inside the shape) / (analytic area of the shape) by Pearson's
// chi-square. The cell areas are integrated independently of the sampler (midpoint rule on a
// 64x64 sub-grid per cell), so the analytic area being right is part of what is tested.
TEST(Camera, ApertureSamplesAreUniformOverTheDiskAndThePolygon) {
    constexpr int kCells = 16, kSub = 64, kN = 400000;
    for (const auto& [blades, rotation] :
         std::vector<std::pair<int, float>>{{0, 0.0f}, {3, 0.0f}, {6, 0.7f}}) {
        std::vector<double> expected(kCells * kCells, 0.0), observed(kCells * kCells, 0.0);
        const double cell = 2.0 / kCells, sub = cell / kSub;
        double integrated_area = 0;
        for (int cy = 0; cy < kCells; ++cy)
            for (int cx = 0; cx < kCells; ++cx) {
                int in = 0;
                for (int j = 0; j < kSub; ++j)
                    for (int i = 0; i < kSub; ++i)
                        in += inside_aperture(-1.0 + cx * cell + (i + 0.5) * sub,
                                              -1.0 + cy * cell + (j + 0.5) * sub, blades, rotation);
                const double area = in * sub * sub;
                integrated_area += area;
                expected[cy * kCells + cx] = kN * area / aperture_area(blades);
            }
        EXPECT_NEAR(integrated_area / aperture_area(blades), 1.0, 2e-3) << blades << " blades";
        std::mt19937 rng(11 + blades);
        std::uniform_real_distribution<float> uni(0.0f, 1.0f);
        int outside = 0;
        double sum_r2 = 0, sum_r4 = 0;
        for (int n = 0; n < kN; ++n) {
            const Vec2 a = sample_aperture({uni(rng), uni(rng)}, blades, rotation);
            const double r2 = double(a.x) * a.x + double(a.y) * a.y;
            sum_r2 += r2;
            sum_r4 += r2 * r2;
            if (!inside_aperture(a.x, a.y, blades, rotation)) {
                // Points on the edge may be a rounding error outside.
                if (!inside_aperture(a.x * (1 - 1e-5), a.y * (1 - 1e-5), blades, rotation)) ++outside;
            }
            const int cx = std::clamp(int((a.x + 1.0f) / cell), 0, kCells - 1);
            const int cy = std::clamp(int((a.y + 1.0f) / cell), 0, kCells - 1);
            observed[cy * kCells + cx] += 1;
        }
        EXPECT_EQ(outside, 0) << blades << " blades";
        const chi_square::ChiSquare r = chi_square::pearson(observed, expected);
        EXPECT_GT(r.p_value, 1e-4) << blades << " blades: chi2 = " << r.statistic << ", dof = " << r.dof;
        // Second moment about the centre: R^2 (2 + cos(2 pi / n)) / 6 for the n-gon (each
        // triangle (0, A, B): (|A|^2 + |B|^2 + A.B) / 6), 1/2 for the disk; within 4 sigma.
        const double mean = sum_r2 / kN, sigma = std::sqrt((sum_r4 / kN - mean * mean) / kN);
        const double want = blades == 0 ? 0.5 : (2.0 + std::cos(2.0 * M_PI / blades)) / 6.0;
        EXPECT_NEAR(mean, want, 4.0 * sigma) << blades << " blades";
    }
}

// ---- C ABI ----------------------------------------------------------------------------------

namespace {

StratumCameraDesc camera_desc() {
    StratumCameraDesc c{};
    c.lens_mm = 50;
    c.sensor_width_mm = 36;
    c.sensor_height_mm = 24;
    c.clip_start = 0.1f;
    c.clip_end = 100;
    const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    std::copy(identity, identity + 16, c.transform);
    return c;
}

std::string set_camera_error(const StratumCameraDesc& c) {
    StratumScene* s = nullptr;
    EXPECT_EQ(stratum_scene_create(&s), STRATUM_OK);
    const StratumStatus status = stratum_scene_set_camera(s, &c);
    std::string error = status == STRATUM_OK ? "" : stratum_last_error();
    stratum_scene_destroy(s);
    return error;
}

std::string file_text(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST(Camera, AbiValidatesTheNewFieldsByName) {
    StratumCameraDesc c = camera_desc();
    EXPECT_EQ(set_camera_error(c), "");  // appended fields all zero: the perspective pinhole
    c.type = 3;
    EXPECT_NE(set_camera_error(c).find("camera type 3"), std::string::npos) << set_camera_error(c);
    c.type = STRATUM_CAMERA_EQUIRECTANGULAR;  // zero ranges: an empty image
    EXPECT_NE(set_camera_error(c).find("latitude_min = 0 must be below latitude_max = 0"), std::string::npos)
        << set_camera_error(c);
    c.latitude_min = -2.0f;
    EXPECT_NE(set_camera_error(c).find("camera latitude_min = -2"), std::string::npos) << set_camera_error(c);
    c.latitude_min = -1.0f;
    c.latitude_max = 1.0f;
    EXPECT_NE(set_camera_error(c).find("longitude_min = 0 must be below"), std::string::npos)
        << set_camera_error(c);
    c.longitude_max = 1.0f;
    EXPECT_EQ(set_camera_error(c), "");
    c.type = STRATUM_CAMERA_ORTHOGRAPHIC;
    EXPECT_NE(set_camera_error(c).find("ortho_scale"), std::string::npos) << set_camera_error(c);
    c.ortho_scale = 3;
    EXPECT_EQ(set_camera_error(c), "");
    c.aperture_radius = -1;
    EXPECT_NE(set_camera_error(c).find("aperture_radius"), std::string::npos) << set_camera_error(c);
    c.aperture_radius = 0.1f;
    EXPECT_NE(set_camera_error(c).find("focus_distance"), std::string::npos) << set_camera_error(c);
    c.focus_distance = 4;
    c.aperture_blades = 2;
    EXPECT_NE(set_camera_error(c).find("aperture_blades"), std::string::npos) << set_camera_error(c);
    c.aperture_blades = 6;
    c.aperture_rotation = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(set_camera_error(c).find("aperture_rotation"), std::string::npos) << set_camera_error(c);
    c.aperture_rotation = 0.5f;
    EXPECT_EQ(set_camera_error(c), "");
}

TEST(Camera, SceneFileKeepsOrthographicAndThinLensFields) {
    StratumCameraDesc c = camera_desc();
    c.type = STRATUM_CAMERA_ORTHOGRAPHIC;
    c.ortho_scale = 3.5f;
    c.aperture_radius = 0.25f;
    c.focus_distance = 4.5f;
    c.aperture_blades = 7;
    c.aperture_rotation = 0.75f;
    StratumScene* scene = nullptr;
    ASSERT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    ASSERT_EQ(stratum_scene_set_camera(scene, &c), STRATUM_OK);
    const std::string a = ::testing::TempDir() + "stratum_camera_a.json";
    const std::string b = ::testing::TempDir() + "stratum_camera_b.json";
    ASSERT_EQ(stratum_scene_save(scene, a.c_str()), STRATUM_OK) << stratum_last_error();
    StratumScene* loaded = nullptr;
    ASSERT_EQ(stratum_scene_load(a.c_str(), &loaded), STRATUM_OK) << stratum_last_error();
    ASSERT_EQ(stratum_scene_save(loaded, b.c_str()), STRATUM_OK) << stratum_last_error();
    const std::string text = file_text(a);
    EXPECT_EQ(text, file_text(b));
    for (const char* key : {"\"type\":1", "\"ortho_scale\":3.5", "\"aperture_radius\":0.25",
                            "\"focus_distance\":4.5", "\"aperture_blades\":7", "\"aperture_rotation\":0.75"})
        EXPECT_NE(text.find(key), std::string::npos) << key << " not in " << text;
    stratum_scene_destroy(scene);
    stratum_scene_destroy(loaded);
    std::remove(a.c_str());
    std::remove(b.c_str());
}

// ---- equirectangular -------------------------------------------------------------------------

namespace {

CameraParams equirect(float lat_min, float lat_max, float lon_min, float lon_max) {
    CameraParams p;
    p.type = CameraType::Equirectangular;
    p.latitude_min = lat_min;
    p.latitude_max = lat_max;
    p.longitude_min = lon_min;
    p.longitude_max = lon_max;
    return p;
}

void expect_direction(const Camera& c, float fx, float fy, Vec3 expected) {
    const CameraRay r = c.generate_ray(fx, fy);
    EXPECT_NEAR(r.direction.x, expected.x, 1e-5f) << "film (" << fx << ", " << fy << ")";
    EXPECT_NEAR(r.direction.y, expected.y, 1e-5f) << "film (" << fx << ", " << fy << ")";
    EXPECT_NEAR(r.direction.z, expected.z, 1e-5f) << "film (" << fx << ", " << fy << ")";
}

}  // namespace

// Cycles' mapping with Blender's camera frame (blender_camera_matrix): the centre looks down the
// camera's −Z, the left edge behind it (+Z), a quarter in to the camera's left (−X), three
// quarters to its right (+X); the bottom row straight down (−Y), the top row straight up.
TEST(Camera, EquirectangularFullSphereDirections) {
    const Camera c(equirect(-0.5f * kPi, 0.5f * kPi, -kPi, kPi), 64, 32);
    expect_direction(c, 32, 16, {0, 0, -1});
    expect_direction(c, 0, 16, {0, 0, 1});
    expect_direction(c, 64, 16, {0, 0, 1});
    expect_direction(c, 16, 16, {-1, 0, 0});
    expect_direction(c, 48, 16, {1, 0, 0});
    expect_direction(c, 32, 0, {0, -1, 0});
    expect_direction(c, 32, 32, {0, 1, 0});
    // Top-right corner: latitude π/2 whatever the longitude; a corner of a partial range below.
    expect_direction(c, 64, 32, {0, 1, 0});
    const CameraRay r = c.generate_ray(32, 16);
    EXPECT_EQ(r.t_min, 0.1f);  // clipping by distance along the ray
    EXPECT_EQ(r.t_max, 1000.0f);
}

// Partial ranges: the image corners look at (longitude, latitude) = (lon_min, lat_min) bottom
// left and (lon_max, lat_max) top right, longitude measured as −φ of Cycles' spherical frame
// (toward the camera's right); the camera transform rotates the result.
TEST(Camera, EquirectangularRangesAndTransform) {
    CameraParams p = equirect(-0.3f, 0.6f, -1.0f, 0.5f);
    p.camera_to_world = looking_along_y();  // local −Z -> world +Y, local Y -> world +Z, X -> X
    const Camera c(p, 30, 20);
    // Panorama-space d(φ, θ) = (sin θ cos φ, sin θ sin φ, cos θ) with φ = −lon, θ = π/2 − lat,
    // seen in the camera frame as (−d.y, d.z, −d.x), then world (x, −z, y).
    const auto world = [](float lon, float lat) {
        const float phi = -lon, theta = 0.5f * kPi - lat;
        const Vec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
        const Vec3 cam(-d.y, d.z, -d.x);
        return Vec3(cam.x, -cam.z, cam.y);
    };
    expect_direction(c, 0, 0, world(-1.0f, -0.3f));
    expect_direction(c, 30, 20, world(0.5f, 0.6f));
    expect_direction(c, 15, 10, world(-0.25f, 0.15f));
    const CameraRay r = c.generate_ray(15, 10);
    EXPECT_NEAR(r.origin.x, 1.0f, 1e-6f);
    EXPECT_NEAR(r.origin.y, 2.0f, 1e-6f);
    EXPECT_NEAR(r.origin.z, 3.0f, 1e-6f);
}

// With an aperture the rays of one film point pass through the same point at focus distance.
TEST(Camera, EquirectangularThinLensFocusesAtTheFocusDistance) {
    CameraParams p = equirect(-0.5f * kPi, 0.5f * kPi, -kPi, kPi);
    p.aperture_radius = 0.2f;
    p.focus_distance = 3.0f;
    const Camera c(p, 64, 32);
    const Camera pinhole(equirect(-0.5f * kPi, 0.5f * kPi, -kPi, kPi), 64, 32);
    const CameraRay centre = pinhole.generate_ray(20.3f, 11.7f);
    const Vec3 focus = centre.origin + centre.direction * 3.0f;
    for (const Vec2 lens : {Vec2{0.1f, 0.9f}, Vec2{0.7f, 0.2f}, Vec2{0.4f, 0.55f}}) {
        const CameraRay r = c.generate_ray(20.3f, 11.7f, lens);
        EXPECT_GT(length(r.origin), 0.01f);
        const Vec3 to = focus - r.origin;
        EXPECT_NEAR(dot(normalize(to), r.direction), 1.0f, 1e-5f);
    }
}

TEST(Camera, SceneFileKeepsEquirectangularRanges) {
    StratumCameraDesc c = camera_desc();
    c.type = STRATUM_CAMERA_EQUIRECTANGULAR;
    c.latitude_min = -0.25f;
    c.latitude_max = 0.75f;
    c.longitude_min = -2.0f;
    c.longitude_max = 1.5f;
    StratumScene* scene = nullptr;
    ASSERT_EQ(stratum_scene_create(&scene), STRATUM_OK);
    ASSERT_EQ(stratum_scene_set_camera(scene, &c), STRATUM_OK) << stratum_last_error();
    const std::string path = ::testing::TempDir() + "stratum_equirect_camera.json";
    ASSERT_EQ(stratum_scene_save(scene, path.c_str()), STRATUM_OK);
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    EXPECT_NE(text.str().find("\"latitude\":[-0.25,0.75]"), std::string::npos) << text.str();
    EXPECT_NE(text.str().find("\"longitude\":[-2.0,1.5]"), std::string::npos) << text.str();
    StratumScene* loaded = nullptr;
    EXPECT_EQ(stratum_scene_load(path.c_str(), &loaded), STRATUM_OK) << stratum_last_error();
    stratum_scene_destroy(loaded);
    stratum_scene_destroy(scene);
    std::remove(path.c_str());
}
