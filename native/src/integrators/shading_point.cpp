#include "integrators/shading_point.h"

namespace stratum {

ShadingPoint build_closures(const RenderScene& scene, const SurfaceHit& hit, Vec3 wo_world) {
    ShadingPoint sp{ClosureSet(scene.material(hit.material_id)), hit.geometric_normal, hit.shading_normal,
                    false};
    sp.backfacing = dot(hit.geometric_normal, wo_world) < 0.0f;
    if (sp.backfacing) sp.ng = -sp.ng;
    // The shading normal is flipped to the viewer's side along with the geometric one.
    if (dot(sp.ns, sp.ng) < 0.0f) sp.ns = -sp.ns;
    WeightedClosure* closures = sp.closures.closures();
    for (uint32_t i = 0; i < sp.closures.count(); ++i) {
        Material& m = closures[i].params;
        if (sp.backfacing && bsdf_has_transmission(m)) m.ior = 1.0f / std::max(m.ior, 1e-5f);
    }
    sp.closures.finalize();
    return sp;
}

}  // namespace stratum
