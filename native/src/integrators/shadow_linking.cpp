#include "integrators/shadow_linking.h"

#include "integrators/ray_offset.h"
#include "sampling/hash.h"

namespace stratum {

namespace {

// Reservoir sampling over a stream: candidate k (1-based) replaces the pick with probability
// 1/k, so each of n candidates ends picked with probability 1/n.
struct Reservoir {
    uint64_t seed;
    ShadowLinkedEmitter pick;
    void offer(const ShadowLinkedEmitter& candidate) {
        const uint32_t k = ++pick.met;
        const float u = bits_to_unit_float(static_cast<uint32_t>(hash_more(seed, k) >> 32));
        if (k == 1 || u * static_cast<float>(k) < 1.0f) {
            const uint32_t met = pick.met;
            pick = candidate;
            pick.met = met;
        }
    }
};

}  // namespace

ShadowLinkedEmitter pick_shadow_linked_emitter(const RenderScene& scene, const ScatteredRay& ray,
                                               uint64_t& rays) {
    const Vec3 origin = ray.origin, dir = ray.dir;
    const RayQuery& query = ray.query;
    const uint8_t receiver_set = ray.receiver_set;
    RayTrack track = ray.track;
    const LightSet& lights = scene.lights();
    const uint64_t blocking_all = lights.shadow_sets_blocking_all_linked();
    Reservoir reservoir{ray.seed, {}};
    // Surfaces: re-spawned past each one (offset along its normal, as shadow rays are), with the
    // distance from `origin` summed for the lamps' range below.
    Vec3 o = origin;
    float travelled = 0.0f, end = kInfinity;
    for (uint32_t surface = 0; surface < kMaxShadowLinkSurfaces; ++surface) {
        SurfaceHit hit;
        ++rays;
        if (!scene.intersect(o, dir, 0.0f, kInfinity, &hit, query)) break;
        const ShadingPoint sp =
            build_closures(scene, hit, -dir, track.at(hit.t, ray.bounces, ray.transparent + surface));
        const float t = travelled + hit.t;
        if (hit.links.shadow_linked() && hit.links.lights(receiver_set)) {
            const Rgb emission = sp.closures.emission();
            if (!emission.is_black()) {
                ShadowLinkedEmitter e;
                e.light = hit.emissive_light;
                e.radiance = emission;
                e.position = hit.position;
                e.t = t;
                e.shadow_sets = hit.links.shadow_set_membership;
                e.lightgroup = hit.lightgroup;
                reservoir.offer(e);
            }
        }
        // Past an opaque surface that blocks every shadow-linked emitter none is seen (header).
        if (sp.closures.transparency().is_black() && ((blocking_all >> hit.links.blocker_shadow_set) & 1u)) {
            end = t;
            break;
        }
        track.pass_through(hit.t);
        travelled = t;
        o = offset_ray_origin(hit.position, dot(hit.geometric_normal, dir) > 0.0f ? hit.geometric_normal
                                                                                  : -hit.geometric_normal);
    }
    // Lamps before the end, met from the ray's origin (they are outside the BVH).
    lights.visit_lamp_hits(
        origin, dir, end, query.visibility, ray.track.at(0.0f, ray.bounces, ray.transparent).path.emission(),
        [&](uint32_t index, float t, Rgb radiance, float solid_angle_pdf) {
            const LightLinks& links = lights.links(index);
            if (!links.shadow_linked() || !links.lights(receiver_set) || radiance.is_black()) return;
            ShadowLinkedEmitter e;
            e.lamp = true;
            e.light = index;
            e.radiance = radiance;
            e.position = origin + dir * t;
            e.t = t;
            e.shadow_sets = links.shadow_set_membership;
            e.casts_shadow = (lights.visibility(index) & kVisibleShadow) != 0;
            e.solid_angle_pdf = solid_angle_pdf;
            e.lightgroup = lights.lightgroup(index);
            reservoir.offer(e);
        });
    return reservoir.pick;
}

}  // namespace stratum
