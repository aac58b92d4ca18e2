/* Stratum C ABI, part 4 of 4: renderers -- settings, start and progress, pixels and passes,
 * one frame's samples over many renders. */
#ifndef STRATUM_RENDER_H
#define STRATUM_RENDER_H

#include "stratum/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- rendering --------------------------------------------------------------------------- */

typedef struct StratumRenderer StratumRenderer;

/* The renderer follows the scene: edits made after this call reach it at its next start (see
 * "live edits"). The scene may be destroyed before the renderer. */
STRATUM_API StratumStatus stratum_renderer_create(const StratumScene* scene, StratumRenderer** out);
STRATUM_API void stratum_renderer_destroy(StratumRenderer* renderer);

/* Named settings (see README "Render settings"):
 *   int:    width, height, samples, max_bounces, seed, threads (0 = all cores),
 *           sample_offset, sample_count (the sample indices rendered: see "one frame's samples"),
 *           crop_x, crop_y, crop_width, crop_height (the border region of the width x height
 *           frame in pixels, bottom-left origin; crop_width = 0 = the whole frame; the image
 *           read and written is the region), film_transparent (1: background alpha 0),
 *           rr_min_depth (first bounce Russian roulette may end a path, default 3),
 *           radiosity_rays (form-factor rays per patch)
 *   float:  filter_width (pixels), ao_distance (scene units, > 0),
 *           control_variate (ambient radiance L_a of the control variate, >= 0; 0 = off),
 *           radiosity_patch_size (scene units, 0 = automatic), radiosity_tolerance
 *   string: sampler (a choice: stratum_setting_choice), filter_type ("box", "blackman_harris"),
 *           integrator (path, light, direct, ao, radiosity), hemisphere (a choice),
 *           radiosity_solver ("shooting", "gauss_seidel", "jacobi"),
 *           light_sampling ("mis", "nee", "bsdf"), mis_heuristic ("power", "balance", "max"),
 *           light_selection ("mixed", "power", "uniform", "tree", "auto"),
 *           triangle_sampling ("solid_angle", "area": how NEE takes a point on an emissive
 *           triangle), rr_mode ("throughput", "albedo", "off"),
 *           passes (comma-separated pass names besides Combined: stratum_pass_info)
 * Setting a name of the wrong kind or an unknown name is STRATUM_ERROR_INVALID_ARGUMENT. */
STRATUM_API StratumStatus stratum_renderer_set_int(StratumRenderer* r, const char* name, int64_t value);
STRATUM_API StratumStatus stratum_renderer_set_float(StratumRenderer* r, const char* name, double value);
STRATUM_API StratumStatus stratum_renderer_set_string(StratumRenderer* r, const char* name,
                                                      const char* value);

/* Starts rendering on native worker threads and returns at once. Builds the BVH on first start. */
STRATUM_API StratumStatus stratum_renderer_start(StratumRenderer* r);
/* What the render cannot show and why, one sentence per line; "" when nothing. Lines come as
 * the render learns them: what the chosen estimator cannot render in this scene (e.g.
 * light_sampling "bsdf" never finds a point light) at stratum_renderer_start; instances skipped
 * as degenerate (a scale of (nearly) 0: their inverse would send rays beyond what Embree
 * accepts) when the scene build ends; the number of samples dropped because their radiance was
 * NaN or infinite, and of rays refused as out of range, when the render ends. *out stays valid
 * until the next call of this function, start or destroy. */
STRATUM_API StratumStatus stratum_renderer_notices(const StratumRenderer* r, const char** out);
/* Asks the render to stop; returns at once. Pixels keep the samples finished so far. */
STRATUM_API StratumStatus stratum_renderer_cancel(StratumRenderer* r);
/* Waits up to timeout_ms for the render to end; *out_done = 1 when it has ended. */
STRATUM_API StratumStatus stratum_renderer_wait(StratumRenderer* r, int32_t timeout_ms, int32_t* out_done);

typedef struct StratumProgress {
    int32_t done; /* 1 when the render has ended (finished or cancelled) */
    int32_t cancelled;
    int32_t samples_done; /* samples that every pixel has */
    int32_t samples_total;
    uint32_t update_serial; /* increases whenever new pixels are available */
    double rays;            /* rays traced so far (camera, bounce and shadow rays) */
    double build_seconds;   /* BVH build time */
    double render_seconds;  /* path-tracing time, without the BVH build */
    double fraction_done;   /* pixel samples finished / (width * height * samples), for progress bars */
    /* What the pass in progress (or the last one started) brings every pixel to: each pixel
     * holds samples_done or samples_in_progress samples. */
    int32_t samples_in_progress;
    /* Samples per pixel on average, from the work finished: samples_done plus the finished part
     * of the pass in progress; it moves as tiles finish (Cycles' "Sample N/M" counts the same). */
    double samples_average;
} StratumProgress;

STRATUM_API StratumStatus stratum_renderer_progress(const StratumRenderer* r, StratumProgress* out);

/* Counters of what the render's features report beyond StratumProgress, each a static name
 * "feature.quantity" and a value of the render in progress (or the last one), 0 when the render
 * does not use the feature. Every renderer has the same counters, index 0 <= index <
 * stratum_progress_counter_count(), in an order that only grows at the end; hosts find them by
 * name. A value is read when asked for (after the render has ended, all are of the finished
 * render):
 *   light_tree.seconds, light_tree.bytes: the light tree the render chooses lights by
 *     (light_selection "tree", or "auto" in a scene of many lights), built before its first
 *     sample: the build's seconds (within render_seconds) and the bytes it holds;
 *   radiosity.patches, radiosity.bytes, radiosity.seconds, radiosity.iterations: the radiosity
 *     integrator's solve, before its first sample: patches K, the most bytes the solve held at
 *     once (patches, form factors, vectors), its seconds (form factors and solver, within
 *     render_seconds) and the solver's iterations;
 *   guiding.nodes, guiding.bytes: path guiding's tree (use_guiding): its nodes and bytes after
 *     the last training pass, updated after each pass, so their growth per pass can be followed.
 * name or value may be NULL. */
STRATUM_API int32_t stratum_progress_counter_count(void);
STRATUM_API StratumStatus stratum_renderer_progress_counter(const StratumRenderer* r, int32_t index,
                                                            const char** name, double* value);

/* The radiosity integrator's solver iterations of the last render, as many as its counter
 * radiosity.iterations: 4 doubles each, in order the textbook's stopping estimate Delta E, Delta E
 * over the mean radiance (what radiosity_tolerance bounds), the residual (both in radiance) and
 * the solver's seconds so far. `count` is the number of doubles the buffer holds: 4 x the
 * iterations. */
STRATUM_API StratumStatus stratum_renderer_read_radiosity_iterations(const StratumRenderer* r, double* out,
                                                                     size_t count);

/* Copies the current image: width*height*4 floats (linear RGBA; for a border render the
 * region's size), rows bottom to top as Blender's render result. `count` is the number of floats the buffer
 * holds. */
STRATUM_API StratumStatus stratum_renderer_read_pixels(const StratumRenderer* r, float* rgba, size_t count);
/* Passes (AOVs) a render can hold besides the image, named as Cycles names them: pass `index`
 * (0 <= index < stratum_pass_count(); 0 is "Combined", the image) has a static name,
 * a channel count and a one-line description. A render holds Combined and the passes its
 * string setting `passes` names (comma-separated). */
STRATUM_API int32_t stratum_pass_count(void);
STRATUM_API StratumStatus stratum_pass_info(int32_t index, const char** name, int32_t* channels,
                                            const char** description);
/* Copies the current values of pass `name`: width*height*channels floats (the region's size),
 * rows bottom to top. A pass the render does not hold is STRATUM_ERROR_INVALID_ARGUMENT. */
STRATUM_API StratumStatus stratum_renderer_read_pass(const StratumRenderer* r, const char* name, float* out,
                                                     size_t count);
/* Copies the current RGB of light group `group` (1..the int setting `lightgroups`; Cycles'
 * "Combined_<name>" passes): width*height*3 floats, rows bottom to top. */
STRATUM_API StratumStatus stratum_renderer_read_lightgroup(const StratumRenderer* r, uint32_t group,
                                                           float* out, size_t count);
/* Writes the current image (EXR linear, or PNG/other by extension via OpenImageIO). */
STRATUM_API StratumStatus stratum_renderer_write_image(const StratumRenderer* r, const char* path);

/* ---- one frame's samples over many renders (machines) ----------------------------------------
 * A render of sample indices [sample_offset, sample_offset + sample_count) of a frame (int
 * settings; the sampler's sequence is that of `samples`) leaves exact fixed-point sums. Those of
 * ranges that meet, added in any order, give the image of the union bit for bit as one render
 * of it. The bytes are in this machine's byte order, for the same library version.
 * _sums_size / _read_sums: the sums of the last render, which must have ended, not cancelled.
 * _add_sums: adds such bytes to the renderer's film (same frame, border region, passes and
 * integrator; the ranges must meet), whose image and passes then show both; a renderer that has
 * rendered nothing takes them as its film (then read_pixels, read_pass, write_image and
 * _read_sums read them). First Sample passes come from the range holding sample 0. */
STRATUM_API StratumStatus stratum_renderer_sums_size(const StratumRenderer* r, size_t* out_bytes);
STRATUM_API StratumStatus stratum_renderer_read_sums(const StratumRenderer* r, void* out, size_t bytes);
STRATUM_API StratumStatus stratum_renderer_add_sums(StratumRenderer* r, const void* sums, size_t bytes);

#ifdef __cplusplus
}
#endif

#endif
