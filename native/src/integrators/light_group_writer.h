// Which of a camera path's contributions reach its emitters' light groups (film/light_groups.h):
// Cycles 3.4 / 5.0 kernel/film/light_passes.h, film_write_direct_light (NEE) and
// film_write_emission_or_background_pass (emission and background that rays meet). Each
// contribution goes, clamped as Combined takes it, to the group of the emitter that produced it.
//
// | contribution                        | path not split    | after a shadow catcher split   |
// |-------------------------------------|-------------------|--------------------------------|
// | NEE (at every vertex)               | its light's group | none (SHADOW_CATCHER_HIT)      |
// | emission, lamp or background a ray  | the emitter's     | Cycles 3.x: the emitter's, of  |
// | meets (camera rays too)             | group             | the main path and of its       |
// |                                     |                   | catcher-only copy; 4.x+: none  |
//
// So without shadow catchers the groups sum to Combined where every emitter is in a group.
#pragma once

#include "film/film.h"
#include "integrators/shadow_catcher.h"

namespace stratum {

class LightGroupWriter {
public:
    // `split_emission`: Cycles 3.x's rule above (IntegratorSettings::lightgroup_split_emission).
    LightGroupWriter(PassValues& passes, const ShadowCatcherPath& catcher, bool split_emission)
        : passes_(passes), catcher_(catcher), split_emission_(split_emission) {}

    void light_sample(uint32_t group, Rgb value) {
        if (!catcher_.split() && !catcher_.is_copy()) passes_.add_lightgroup(group, value);
    }
    void emission(uint32_t group, Rgb value) {
        // The copy's light before its split is the main path's, written by it.
        if (catcher_.split() ? split_emission_ : !catcher_.is_copy()) passes_.add_lightgroup(group, value);
    }

private:
    PassValues& passes_;
    const ShadowCatcherPath& catcher_;
    bool split_emission_;
};

}  // namespace stratum
