#include "integrators/shading_point.h"

#include "integrators/valid_reflection_normal.h"
#include "render_scene/material_texturing.h"

namespace stratum {

ShadingPoint build_closures(const RenderScene& scene, const SurfaceHit& hit, Vec3 wo_world, RayReach reach,
                            const ClosureFilter& filter) {
    ShadingPoint sp{scene.closure_set(hit.material_id), hit.geometric_normal, hit.shading_normal, false};
    Vec3 smooth = hit.shading_normal;
    // The set was finalized from the material as stored (RenderScene::closure_set); only a changed parameter
    // needs it again.
    bool changed = false;
    // Textures first, on the winding-oriented normal: a normal map's tangent frame (T, sign
    // cross(N, T), N) is defined for it, and the flip below then applies to the mapped normal.
    if (!scene.textures().of_material(hit.material_id).empty()) {
        apply_texture_bindings(scene.textures(), hit.material_id, hit.uv, hit.tangent_frame,
                               sp.closures.closures(), sp.closures.count(), &sp.ns);
        changed = true;
    }
    sp.backfacing = dot(hit.geometric_normal, wo_world) < 0.0f;
    // Node programs after the images: a program's Normal output replaces a normal map's, as a
    // node wired to the BSDF's Normal replaces what Cycles' default would be.
    if (scene.programs().any(hit.material_id)) {
        scene.programs().apply(hit, scene.program_inputs(hit, wo_world, sp.backfacing, reach),
                               sp.closures.closures(), sp.closures.count(), &sp.ns);
        changed = true;
    }
    // Both normals turn to the viewer's side together (Cycles: SD_BACKFACING negates Ng and N).
    // A shading normal that still points below the surface (a smooth mesh's interpolated normal
    // at a sharp fold) is not mirrored: the bend below keeps the side it leans to, as Cycles 3.x
    // does, and lifts it above the surface.
    if (sp.backfacing) {
        sp.ng = -sp.ng;
        sp.ns = -sp.ns;
        smooth = -smooth;
    }
    sp.ns = ensure_valid_reflection(sp.ng, wo_world, sp.ns);
    // Cycles compares the closure normal with sd->N exactly (isequal): any change, by a normal
    // map or by the bend above, brings in the bump shadowing term.
    if (!(sp.ns.x == smooth.x && sp.ns.y == smooth.y && sp.ns.z == smooth.z)) {
        sp.closures.set_smooth_normal(Frame::from_normal(sp.ns).to_local(smooth));
    }
    WeightedClosure* closures = sp.closures.closures();
    for (uint32_t i = 0; i < sp.closures.count(); ++i) {
        Material& m = closures[i].params;
        if (sp.backfacing && bsdf_has_transmission(m)) {
            m.ior = 1.0f / std::max(m.ior, 1e-5f);
            changed = true;
        }
    }
    if (filter.active()) {
        sp.closures.apply(filter);
        changed = true;
    }
    if (changed) sp.closures.finalize();
    return sp;
}

}  // namespace stratum
