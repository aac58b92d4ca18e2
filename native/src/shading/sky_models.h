// The daylight models of Blender's Sky Texture, as pure math (no node code): the evaluation of
// Preetham's and Hosek-Wilkie's analytic skies from their packed coefficients, and Nishita's
// single-scattering atmosphere precomputed into a table (Blender 3.x's intern/sky/source/
// sky_nishita.cpp, which Cycles 3.4 bakes at 512 x 128 texels; Cycles' own third_party copy at
// v3.4.0 is older: it marches the sun's optical depth where Blender integrates it by Gauss-Laguerre,
// 0.6% to 7% apart, and Blender 3.4 matches the latter to 1e-5).
//
// References: A. J. Preetham, P. Shirley, B. Smits, "A Practical Analytic Model for Daylight"
// (SIGGRAPH 1999); L. Hosek, A. Wilkie, "An Analytic Model for Full Spectral Sky-Dome Radiance"
// (SIGGRAPH 2012); T. Nishita et al., "Display of the Earth Taking into Account Atmospheric
// Scattering" (SIGGRAPH 1993). Cycles: kernel/svm/sky.h, scene/shader_nodes.cpp SkyTextureNode.
#pragma once

#include <vector>

#include "core/math.h"

namespace stratum::sky {

// The coefficients of Preetham's and Hosek-Wilkie's models as Cycles packs them (32 floats): the
// sun's phi and theta, the three channels' zenith radiances, then 9 configuration values per
// channel. Preetham's channels are Y, x, y (the perez coefficients in the first 5 of each);
// Hosek-Wilkie's are X, Y, Z.
inline constexpr int kAnalyticDataCount = 32;

// Which XYZ to Rec.709 matrix (xyz_to_rec709 below): that of Blender's colour configuration
// (the add-on's blender_versions.color_config), 3.x, 4.0 to 4.5, or 5.0 and later.
enum class XyzMatrix { Blender3, Blender4, Blender5 };

// Preetham's sky for direction `dir` (not normalised, as Cycles reads it), in linear Rec.709.
Rgb preetham(const float* data, Vec3 dir, XyzMatrix m);
// Hosek-Wilkie's sky, scaled by 2 pi / 683 as Cycles scales it, in linear Rec.709.
Rgb hosek_wilkie(const float* data, Vec3 dir, XyzMatrix m);

// CIE XYZ (D65) to linear Rec.709, negative components clamped to 0 (Cycles' xyz_to_rgb_clamped
// with Blender's default colour management). The matrix is the configuration's: Blender 3.x's
// goes through its srgb_to_xyz.spimtx (the 4-digit sRGB primaries), 4.0 to 4.5's from "Linear
// CIE-XYZ D65" by a 16-digit BT.709 matrix (within 2e-5 of 3.x's), 5.0's by the 7-digit BT.709
// matrix (2.4e-4 from both).
Rgb xyz_to_rec709(Vec3 xyz, XyzMatrix m);

// Nishita's atmosphere, Blender 3.x. The parameters as the node holds them.
struct NishitaParams {
    float sun_elevation = 0.0f;  // radians
    float sun_size = 0.0f;       // angular diameter, radians (clamped to >= 0.0005 as Cycles)
    float altitude = 0.0f;       // metres (clamped to [1, 59999] as Cycles)
    float air_density = 1.0f, dust_density = 1.0f, ozone_density = 1.0f;
};

inline constexpr int kNishitaWidth = 512;   // longitudes over the full circle
inline constexpr int kNishitaHeight = 128;  // elevations 0 .. pi/2, denser toward the horizon

// The sky's XYZ radiance for every texel: row y at elevation (pi/2 + pi/(4 height)) (y/height)^2,
// column x at longitude 2 pi x / width - pi from the sun, mirrored about the sun's meridian;
// kNishitaWidth * kNishitaHeight * 3 floats, rows from the horizon up.
std::vector<float> nishita_sky_table(const NishitaParams& p);

// Blender 5.x's single scattering (SINGLE_SCATTERING, intern/sky sky_single_scattering.cpp): the
// same atmosphere over the whole sphere, kNishitaWidth x kSingleScatteringHeight texels; rows
// from the bottom, row y at |elevation| pi/2 (y/(height/2) - 1)^2, the upper half the sky and the
// lower half the horizon row faded by (1 - 2.5 sin|elevation|)^3 (black from sin 0.4).
inline constexpr int kSingleScatteringHeight = 256;
std::vector<float> single_scattering_table(const NishitaParams& p);

// Blender 5.x's MULTIPLE_SCATTERING (sky_multiple_scattering.cpp): the same table layout as
// single_scattering_table but every row computed (rows at elevation copysign(l^2, l) pi/2,
// l = 2 (y + 0.5)/height - 1; columns at azimuth 2 pi (x + 0.5)/width), and the sun's pixels.
std::vector<float> multiple_scattering_table(const NishitaParams& p);
void multiple_scattering_sun_pixels(const NishitaParams& p, Vec3& bottom, Vec3& top);

// Blender 5.x: the angle below the horizon at which a viewer at `altitude` metres sees the Earth's
// limb, pi/2 - asin(R / (R + altitude)) with R = 6371 km.
float earth_intersection_angle(float altitude);

// The sun disc's XYZ radiance at its lowest and highest point (each clamped to the horizon):
// the sun's irradiance over the disc's solid angle, attenuated by Rayleigh and Mie extinction
// along the ray to the sun (no ozone, as Blender 3.x).
void nishita_sun_pixels(const NishitaParams& p, Vec3& bottom, Vec3& top);

}  // namespace stratum::sky
