/* Stratum C ABI, part 2 of 4: what works without a scene -- sample points and hemisphere warps
 * (for `stratum points` and studies), the blue-noise texture, vertex normals. */
#ifndef STRATUM_HELPERS_H
#define STRATUM_HELPERS_H

#include "stratum/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- sampling, without a scene (for `stratum points` and studies) ----------------------- */

/* Name of sample dimension `dimension` in the named layout ("filter.x", "bounce0.light_choice",
 * "bounce1.bsdf.u", ...). Dimensions are unbounded (bounce blocks repeat); every index has a name. */
STRATUM_API StratumStatus stratum_dimension_name(uint32_t dimension, const char** out_name);
/* Dimensions before the first bounce block, and the size of each bounce block. */
STRATUM_API uint32_t stratum_camera_dimensions(void);
STRATUM_API uint32_t stratum_bounce_dimension_stride(void);

/* The first `count` samples (indices 0..count-1) of pixel (pixel_x, pixel_y) of a
 * width x height image rendered with `samples` samples per pixel and `seed`, in dimensions
 * dim_a and dim_b: out_xy receives count pairs. dim_a, dim_b may be any dimensions; when
 * dim_b == dim_a + 1 and dim_a is even the sampler's 2D pair is used, as the integrators do. */
STRATUM_API StratumStatus stratum_sampler_points(const char* sampler, uint32_t samples, uint32_t seed,
                                                 uint32_t width, uint32_t height, uint32_t pixel_x,
                                                 uint32_t pixel_y, uint32_t dim_a, uint32_t dim_b,
                                                 uint32_t count, float* out_xy);
/* Maps count points of [0,1)^2 (uv, 2 floats each) through a hemisphere distribution
 * (a choice of the "hemisphere" setting): out_xyz receives unit vectors (z = normal) and
 * out_pdf (optional) their solid-angle densities. */
STRATUM_API StratumStatus stratum_warp_hemisphere(const char* distribution, const float* uv, uint32_t count,
                                                  float* out_xyz, float* out_pdf);
/* The `bluenoise` sampler's 128 x 128 void-and-cluster texture, row-major (texel (x, y) at
 * y*128 + x): out receives (rank + 0.5)/16384 per texel, the values the sampler reads.
 * count must be 128*128. The texture is generated on first use (about a second). */
STRATUM_API StratumStatus stratum_bluenoise_texture(float* out, uint32_t count);

/* ---- mesh helpers (no scene) --------------------------------------------------------------- */

/* Angle-weighted vertex normals of a polygon mesh, the same bits on every call and for any
 * `threads` (0 = all cores): each vertex's normal is the normalised sum over its corners, in face
 * order then corner order, of (its face's normal) x (the corner's interior angle); a vertex whose
 * sum is zero takes its position's direction (Blender 3.x's definition and fallback; Blender < 4.1
 * sums with atomic adds, so its own normals differ in their last bits between evaluations).
 * positions: 3 floats per vertex; face f has face_sizes[f] >= 1 corners starting at corner
 * face_starts[f], within corner_count, and the faces have at most corner_count corners in all;
 * face_normals: 3 floats per face; corner_vertices: a vertex index per corner. Writes 3 floats
 * per vertex into out_normals. Arrays of a zero count may be NULL. */
STRATUM_API StratumStatus stratum_vertex_normals(uint32_t vertex_count, const float* positions,
                                                 uint32_t face_count, const uint32_t* face_starts,
                                                 const uint32_t* face_sizes, const float* face_normals,
                                                 uint32_t corner_count, const uint32_t* corner_vertices,
                                                 uint32_t threads, float* out_normals);

#ifdef __cplusplus
}
#endif

#endif
