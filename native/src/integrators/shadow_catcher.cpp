#include "integrators/shadow_catcher.h"

#include <algorithm>

#include "integrators/integrator.h"

namespace stratum {

bool has_shadow_catcher(const Scene& scene) {
    return std::ranges::any_of(scene.instances, [](const Instance& i) {
        return !i.holdout && (i.visibility & kVisibleShadowCatcher);
    });
}

CatcherCombined catcher_combined_shown(const Scene& scene, const Integrator& integrator,
                                       std::span<const Pass> passes, bool film_transparent) {
    if (!integrator.splits_shadow_catchers() || !has_shadow_catcher(scene)) return CatcherCombined::Off;
    if (std::ranges::find(passes, Pass::ShadowCatcher) != passes.end()) return CatcherCombined::Matte;
    return film_transparent ? CatcherCombined::MatteWithShadow
                            : CatcherCombined::MatteWithShadowOverBackground;
}

std::vector<std::string> unsplit_catcher_notices(const Scene& scene, const Integrator& integrator,
                                                 const std::string& name) {
    if (integrator.splits_shadow_catchers() || !has_shadow_catcher(scene)) return {};
    return {"the " + name +
            " integrator renders shadow catchers as ordinary objects (only 'path' splits camera paths at "
            "them): Combined shows them, and the Shadow Catcher pass is 1"};
}

void ShadowCatcherPath::split_here(Rgb beta, float transparency, Rgb background, Rgb& L) {
    split_ = true;
    if (role_ == Role::Copy) {
        L = Rgb(0.0f);
        catcher_only_ = true;
        return;
    }
    matte_ = L;
    matte_transparency_ = transparency + beta.average();
    background_ += beta * background;
}

ShadowCatcherSample ShadowCatcherPath::sample(Rgb main_radiance, float main_alpha, Rgb catcher_light) const {
    ShadowCatcherSample s;
    s.catcher = catcher_light;
    // A path that never split is matte all along.
    s.matte = split_ ? matte_ : main_radiance;
    s.matte_transparency = split_ ? matte_transparency_ : 1.0f - main_alpha;
    s.split = split_ ? 1.0f : 0.0f;
    s.background = background_;
    return s;
}

}  // namespace stratum
