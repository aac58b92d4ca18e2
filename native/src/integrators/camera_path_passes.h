// The data passes and denoising features a camera path writes (film/passes.h), as Cycles writes
// them (kernel/film/data_passes.h, kernel/film/denoising_passes.h, 3.4 to 5.0):
//
// | pass             | value of one camera sample                                             |
// |------------------|------------------------------------------------------------------------|
// | Depth, Position  | at each surface the path meets while it is still camera-visible (only  |
// |                  | transparent pass-throughs so far), until one with alpha >= 0.5 (Cycles' |
// |                  | default pass_alpha_threshold, alpha = 1 − average transparency): its   |
// |                  | Camera::z_depth and world position; a miss: kBackgroundDepth and 0      |
// | Normal           | that opaque surface's world shading normal (0 on a miss)               |
// | Denoising Albedo | β (the path's throughput) × the closures' albedo at the first surface  |
// |                  | with a non-delta closure, plus β × emission, lamps and background met  |
// |                  | before it. Delta-only surfaces (mirror, smooth glass, transparency) are |
// |                  | followed with the sampled weight, whose mean is the specular albedo    |
// |                  | Cycles multiplies in (denoising_feature_throughput *= specular_albedo). |
// | Denoising Normal | that surface's shading normal in Camera::to_view_space (Cycles' camera |
// |                  | space); 0 on a miss or a surface that scatters nothing                 |
// | UV               | that opaque surface's (u, v, 0), with Normal (0 on a miss)             |
// | IndexOB, IndexMA | with Depth: the surface's object and material pass index (0 on a miss) |
// | Emit, Env        | β × the emission of surfaces and lamps, and β × the background, met    |
// |                  | while the path is camera-visible (Cycles' emission and background      |
// |                  | passes: contributions before PATH_RAY_ANY_PASS is set)                 |
// | Mist             | 1 − Σ (1 − m(d)) average(β α) over the camera-visible surfaces, α their |
// |                  | opacity, d Camera::distance, m(d) = clamp((d − start)/depth, 0, 1) to   |
// |                  | the power falloff (Cycles' film_write_data_passes; 1 on a miss)          |
// | AO               | Σ β α [a cosine direction about ns is unblocked within ao_distance]     |
// |                  | over the camera-visible surfaces (Cycles' integrate_surface_ao: one     |
// |                  | shadow ray each, drawn from the surface's BSDF direction numbers)       |
// | DiffCol, GlossCol| Σ β × the closures' colours (ClosureSet::colors: Cycles' surface_shader_ |
// | TransCol         | diffuse/glossy/transmission) over the camera-visible surfaces, as       |
// |                  | Cycles' film_write_data_passes adds them (0 on a miss; the AO           |
// |                  | integrator's plain surfaces count as white diffuse)                     |
//
// Differences from Cycles, kept because Stratum's closures are whole models: Cycles defers to
// the next bounce when ≥ 75% of the sample weight is specular-like (GGX alpha ≤ 0.075) and
// writes only the diffuse-like closures' albedo; Stratum defers at delta-only surfaces and
// writes the closures' albedo (ClosureSet::denoising_albedo: base colour for one-lobe models;
// for Cycles 3.x's Principled the estimate base colour + 0.04, for 4.x's the sum of its colour
// passes, which are Cycles 4.x's bsdf_albedo estimates at the view angle).
#pragma once

#include "bsdf/closure_set.h"
#include "film/film.h"
#include "render_scene/render_scene.h"

namespace stratum {

// Blender's world mist settings (World > Mist Pass): start and depth in scene units, falloff the
// exponent (quadratic 2, linear 1, inverse quadratic 0.5).
struct MistSettings {
    float start = 5.0f;
    float depth = 25.0f;
    float falloff = 2.0f;
};

class CameraPathPasses {
public:
    CameraPathPasses(PassValues& passes, const MistSettings& mist);
    // A surface the path meets (`hit`) with shading normal `ns`; `beta` is the path's
    // throughput up to it and `camera_visible` whether only transparent pass-throughs came before.
    // `wo_world` points from the surface toward the viewer.
    // `emission_clamp`: the clamp of the light the surface's emission adds (clamp_contribution's
    // limit), so that Emit holds what Combined holds of it, as Cycles writes every pass after its
    // clamp; 0 = none.
    void surface(const SurfaceHit& hit, Vec3 ns, Vec3 wo_world, const ClosureSet& closures, Rgb beta,
                 bool camera_visible, float emission_clamp = 0.0f);
    // A surface without closures (the AO integrator's): white albedo, opaque.
    void plain_surface(const SurfaceHit& hit, Vec3 ns);
    // Lamp radiance the path collects (times β and its MIS weight), camera-visible or not.
    void emitted(Rgb contribution, bool camera_visible) {
        if (features_pending_) albedo_ += contribution;
        if (direct_ && camera_visible) emit_ += contribution;
    }
    // The AO pass's shadow ray from a camera-visible surface at `position` (true normal ng,
    // shading normal ns), with direction numbers u; `weight` = β × the surface's opacity.
    bool wants_ao() const { return passes_.wants(Pass::Ao); }
    void ao(const RenderScene& scene, Vec3 position, Vec3 ns, Vec3 ng, Vec2 u, Rgb weight, float time,
            float distance, uint64_t& rays);
    // The path leaves the scene; `background` (times β, clamped as Combined takes it) is what it
    // collects there.
    void miss(Rgb background, bool camera_visible);
    // Whether the path still has something to write (cheap test before computing arguments).
    bool pending() const { return data_pending_ || features_pending_ || direct_ || mist_wanted_; }
    // Writes what the path gathered (call once, when the path ends).
    void finish();

private:
    // The passes measured in the camera's space need PassValues::camera (the renderer gives
    // it; without one they stay 0).
    void write_depth(Vec3 position);
    // Depth, Position and the pass indices of a camera-visible surface.
    void write_first_surface(const SurfaceHit& hit);
    void write_features(Vec3 ns, Rgb albedo);
    // Adds a camera-visible surface at `position` of opacity average(weight) to the mist.
    void add_mist(Vec3 position, Rgb weight);

    PassValues& passes_;
    const MistSettings& mist_;
    bool data_pending_, features_pending_, direct_, mist_wanted_, colors_wanted_;
    float mist_sum_ = 0.0f;
    Rgb albedo_{0.0f}, emit_{0.0f}, env_{0.0f}, ao_{0.0f};
    Rgb diffuse_color_{0.0f}, glossy_color_{0.0f}, transmission_color_{0.0f};
};

}  // namespace stratum
