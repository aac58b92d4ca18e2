// Cycles' shadow catcher in a camera path (Cycles 3.4 / 5.0 integrator/shadow_catcher.h,
// intersect_closest.h integrator_split_shadow_catcher, film/light_passes.h
// film_write_shadow_catcher*): the path splits at its first catcher hit; the main path goes on
// seeing the whole scene and writes Combined, and a copy of it from that hit on sees only the
// catchers (their geometry, shadow rays, emission) and the lights that light them, and writes
// the catcher-only buffer. Light written before the split, or by a path that never split, is
// the matte. The film turns these sums into the Shadow Catcher pass and Combined's matte
// (film/shadow_catcher_film.h).
//
// | condition of the split (all)   | Cycles                                              |
// |--------------------------------|-----------------------------------------------------|
// | the hit instance is a catcher  | SD_OBJECT_SHADOW_CATCHER (object.is_shadow_catcher) |
// | and not a holdout              | SD_OBJECT_HOLDOUT_MASK: a holdout catcher never splits |
// | camera-visible path            | PATH_RAY_TRANSPARENT_BACKGROUND: only camera and    |
// |                                | transparent vertices so far                         |
// | not split before               | PATH_RAY_SHADOW_CATCHER_HIT                         |
//
// The copy is traced as the main path again from the camera with the same random numbers: up to
// the split it retraces the main path exactly (the same state at the catcher hit as Cycles'
// copied state), drops the light it summed there (the main path's matte) and from the hit on
// traces the catcher-only scene, whose rays carry the visibility bits shifted by
// kCatcherPathShift (scene/visibility.h).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "core/math.h"
#include "film/shadow_catcher_film.h"
#include "render_scene/render_scene.h"
#include "scene/visibility.h"

namespace stratum {

class Integrator;

// Whether some instance of `scene` is a shadow catcher that is not a holdout.
bool has_shadow_catcher(const Scene& scene);
// What Combined shows of `scene`'s shadow catchers when `integrator` renders these passes
// (Cycles' sync_film: the approximate matte with shadow unless the Shadow Catcher pass is asked
// for; over the background when the film is not transparent).
CatcherCombined catcher_combined_shown(const Scene& scene, const Integrator& integrator,
                                       std::span<const Pass> passes, bool film_transparent);
// The notice of an integrator that renders shadow catchers as plain objects (none when it
// splits paths at them or `scene` has no catcher).
std::vector<std::string> unsplit_catcher_notices(const Scene& scene, const Integrator& integrator,
                                                 const std::string& name);

class ShadowCatcherPath {
public:
    // The main path of a camera sample; `scene_has_catcher` false: nothing changes.
    static ShadowCatcherPath main(bool scene_has_catcher) {
        return ShadowCatcherPath(scene_has_catcher ? Role::Main : Role::Off);
    }
    // The catcher-only copy of a main path that split.
    ShadowCatcherPath copy() const { return ShadowCatcherPath(Role::Copy); }

    bool active() const { return role_ != Role::Off; }
    bool is_copy() const { return role_ == Role::Copy; }
    bool split() const { return split_; }

    // Whether the path splits at this surface hit: the conditions above.
    bool splits_at(const SurfaceHit& hit, bool camera_visible_path) const {
        return role_ != Role::Off && !split_ && camera_visible_path && !hit.holdout &&
               (hit.visibility & kVisibleShadowCatcher);
    }
    // The split, where splits_at says so. The main path records its matte (the light `L` so far,
    // the transparency so far plus the throughput β's mean, Cycles'
    // film_write_shadow_catcher_bounce_data) and the background along the ray (the Background pass
    // the copy writes at the split; asked for only here, as a world program may run for it); the
    // copy drops `L` and sees only catchers from here on.
    void split_here(Rgb beta, float transparency, Rgb background, Rgb& L);
    // A camera-visible ray of the main path left the scene: β × the background it saw.
    void camera_miss(Rgb seen) {
        if (role_ == Role::Main) background_ += seen;
    }

    // The visibility bits a ray of this kind carries on this path.
    uint32_t ray_visibility_bits(uint32_t bits) const {
        return catcher_only_ ? bits << kCatcherPathShift : bits;
    }
    RayQuery query(const RayQuery& q) const { return {q.time, ray_visibility_bits(q.visibility)}; }
    // The StratumVisibility bits of a light (LightSample::visibility) as this path reads them: in the
    // catcher-only scene, those of its catcher-path copy (none for a light that does not light it).
    uint32_t light_visibility(uint32_t trace_bits) const {
        return catcher_only_ ? (trace_bits >> kCatcherPathShift) & kVisibleAll : trace_bits & kVisibleAll;
    }

    // The film's shadow catcher sums of the camera sample: `main` the main path's radiance and
    // alpha, `catcher_light` the copy's radiance (0 when it did not split).
    ShadowCatcherSample sample(Rgb main_radiance, float main_alpha, Rgb catcher_light) const;

private:
    enum class Role : uint8_t { Off, Main, Copy };
    explicit ShadowCatcherPath(Role role) : role_(role) {}

    Role role_;
    bool split_ = false;
    bool catcher_only_ = false;
    Rgb matte_{0.0f};
    float matte_transparency_ = 0.0f;
    Rgb background_{0.0f};
};

}  // namespace stratum
