// Blender's perspective, orthographic and equirectangular cameras: lens, ortho_scale, sensor size and fit,
// shift, clipping and thin-lens depth of field, computed as Blender's
// BKE_camera_params_compute_viewplane and Cycles' camera do, so Stratum frames exactly what
// Cycles frames.
//
// | parameter         | meaning (Blender name) |
// |-------------------|------------------------|
// | type              | type: PERSP or ORTHO |
// | lens_mm           | focal length (lens), perspective |
// | ortho_scale       | ortho_scale: extent of the fitted image side in scene units, orthographic |
// | sensor_*_mm       | sensor_width / sensor_height |
// | fit               | sensor_fit: AUTO uses sensor_width (ortho_scale) along the larger image side |
// | shift_x/y         | lens shift, in units of the fitted image side |
// | clip_start/end    | ray extent along the view direction (by depth) |
// | aperture_radius   | Cycles' aperture size: lens/(2 fstop) (ortho 1/(2 fstop)); 0 = pinhole |
// | focus_distance    | dof.focus_distance: depth of the plane in focus |
// | aperture_blades   | dof.aperture_blades: 0 = disk, n >= 3 = regular n-gon inscribed in the radius |
// | aperture_rotation | dof.aperture_rotation (radians): turns the n-gon counter-clockwise |
// | latitude_min/max  | equirectangular: latitude at the bottom / top image edge (radians) |
// | longitude_min/max | equirectangular: longitude (−φ below) at the left / right image edge |
//
// Thin lens (Cycles' model): the ray starts at a uniform point of the aperture (radius
// aperture_radius, on the plane z = 0 of the pinhole, or of the film point when orthographic)
// and passes through the point the pinhole ray reaches at depth focus_distance, so the plane
// at that depth is sharp.
//
// Equirectangular (Cycles 3.4 and 5.0 kernel/camera/projection.h equirectangular_range_to_direction,
// scene/camera.cpp equirectangular_range, blender/camera.cpp blender_camera_matrix): film point
// (u, v) in [0,1]^2 (v = 0 at the bottom) maps to
//     φ = (lon_min − lon_max) u − lon_min,   θ = (lat_min − lat_max) v − lat_min + π/2,
//     d = (sin θ cos φ, sin θ sin φ, cos θ)   in Cycles' panorama space,
// which Blender's camera frame sees as (−d.y, d.z, −d.x): the image centre (φ = 0, θ = π/2 for
// symmetric ranges) looks down the camera's −Z, u grows toward the camera's +X (φ decreasing),
// v toward +Y. Clipping is by distance along the ray. A thin lens (Cycles' camera_sample_panorama)
// aims from a point of the aperture disk, spanned by U = normalize(x − d.x d), V = d × U in
// panorama space, at d · focus_distance.
#pragma once

#include <cstdint>

#include "core/math.h"

namespace stratum {

enum class SensorFit : int32_t { Auto = 0, Horizontal = 1, Vertical = 2 };
enum class CameraType : int32_t { Perspective = 0, Orthographic = 1, Equirectangular = 2 };

struct CameraParams {
    CameraType type = CameraType::Perspective;
    float lens_mm = 50.0f;
    float ortho_scale = 6.0f;
    float sensor_width_mm = 36.0f;
    float sensor_height_mm = 24.0f;
    SensorFit fit = SensorFit::Auto;
    float shift_x = 0.0f, shift_y = 0.0f;
    float clip_start = 0.1f, clip_end = 1000.0f;
    float aperture_radius = 0.0f;
    float focus_distance = 0.0f;
    int32_t aperture_blades = 0;
    float aperture_rotation = 0.0f;
    float latitude_min = -kPi / 2, latitude_max = kPi / 2;
    float longitude_min = -kPi, longitude_max = kPi;
    Transform camera_to_world;
};

struct CameraRay {
    Vec3 origin;
    Vec3 direction;  // unit length
    float t_min, t_max;
    // Shutter time in [0,1] the ray samples (motion blur). The renderer sets it: drawn from the
    // sampler at kDimTime when the scene has motion, 0.5 otherwise.
    float time = 0.5f;
    // Cycles' compact ray differentials: the spread of the ray's origin (`dp`) and direction
    // (`dd`) to the next pixel's, so that dp + t dd is the footprint t along the ray (sd->dP).
    float dp = 0.0f, dd = 0.0f;
};

// A scene point seen from a point of the lens (light tracing's camera connection, textbook
// 6.8–6.9). With the film in pixels and the view plane at unit depth, a pixel covers
// A_pix = (right − left)(top − bottom)/(W H) of it; the solid angle of film area ds seen at
// angle θ from the axis is A_pix cos³θ ds, and from a scene point x at distance r with
// surface cosine c_x, dω = c_x dA/r². A pixel's measurement ∫ h(s) L ds (h the filter's
// normalised weight) is therefore ∫ h(s(x)) L(x→z) c_x / (r² A_pix cos³θ) dA_x. The thin
// lens gives the same factor: for a fixed lens point z, film point s maps to the point of the
// focus plane the ray z→x crosses, dω = cos³θ A_pix ds again (θ the angle of that ray to the
// axis); the uniform lens pdf 1/A_apert of the camera rays cancels against sampling z
// uniformly on the aperture (6.9: p(z) = 1/A_apert).
struct CameraConnection {
    Vec3 lens_point;   // z, world
    Vec3 to_camera;    // unit, from x toward z
    float distance;    // |z − x|
    float unclipped;   // the part of the segment from x that lies beyond the near clip plane
    Vec2 film;         // film position of x in pixels (as generate_ray's fx, fy)
    float importance;  // 1 / (r² A_pix cos³θ): times c_x, the density conversion above
};

// Maps u in [0,1)^2 uniformly onto the unit aperture: the unit disk (blades 0, concentric map)
// or the regular n-gon inscribed in it (blades n >= 3) whose vertices lie at the angles
// rotation + (2k+1) pi/n, as Cycles' regular_polygon_sample (an edge faces the angle
// `rotation`): one of the n equal triangles (centre, vertex k-1, vertex k) is chosen by u.x,
// u.x rescaled to [0,1) is reused, then a uniform point in the triangle.
Vec2 sample_aperture(Vec2 u, int32_t blades, float rotation);

class Camera {
public:
    Camera(const CameraParams& params, uint32_t width, uint32_t height);
    // Ray through the film position (fx, fy) in pixels: (0,0) is the bottom-left corner of the
    // image, (width, height) the top-right, as Blender's render result rows run bottom to top.
    // `lens` in [0,1)^2 picks the point on the aperture (ignored for a pinhole). The ray carries
    // Cycles' differentials (CameraRay::dp, dd).
    CameraRay generate_ray(float fx, float fy, Vec2 lens = {0.5f, 0.5f}) const;
    bool has_aperture() const { return params_.aperture_radius > 0.0f; }
    // Perspective cameras (pinhole or thin lens): connects the world point x to the lens point
    // `lens` picks (as generate_ray uses it; ignored for a pinhole). False when x lies outside
    // the clipping depths or the camera is not perspective (orthographic and panoramic cameras
    // have no connection: a particle never reaches their film by a finite lens).
    bool connect(Vec3 x, Vec2 lens, CameraConnection* out) const;
    CameraType type() const { return params_.type; }
    // Cycles' camera_z_depth (kernel/camera/camera.h): the depth of x along the view axis for
    // perspective and orthographic cameras, its distance from the camera for panoramic ones.
    float z_depth(Vec3 x) const;
    // Cycles' camera_distance: |x − camera| (orthographic: the distance along the view axis).
    float distance(Vec3 x) const;
    // A world direction in Cycles' camera space (x right, y up, z forward: Blender's camera
    // axes with z negated, its scale cleared as Cycles clears it), as Cycles' Denoising Normal.
    Vec3 to_view_space(Vec3 direction) const;
    // The view plane: at unit distance in front of the camera (perspective) or at the camera
    // (orthographic, scene units): [left,right] x [bottom,top].
    float left() const { return left_; }
    float right() const { return right_; }
    float bottom() const { return bottom_; }
    float top() const { return top_; }

private:
    // The ray through (fx, fy), through the lens point `lens` picks or (through_lens false) the
    // pinhole, without differentials.
    CameraRay ray(float fx, float fy, Vec2 lens, bool through_lens) const;
    CameraRay equirectangular_ray(float fx, float fy, Vec2 lens, bool through_lens) const;

    CameraParams params_;
    float inv_width_, inv_height_;
    Transform world_to_camera_;  // inverse of camera_to_world
    float left_, right_, bottom_, top_;
};

}  // namespace stratum
