// All lights of a scene and the discrete distributions that next-event estimation (and the
// light tracer's emission) choose them by, one per LightSelection:
// * power (textbook 5.14): p(j) = Φ_j / ΣΦ;
// * uniform: p(j) = 1/N over the N light entries (each emissive triangle is an entry);
// * mixed (the default): pure power-proportional choice starves a light whose power estimate is
//   small next to another's although it dominates somewhere (a dim lamp beside a sun whose
//   "power" is its flux through the whole scene): its few samples carry huge weights and the
//   image shows dark pixels where it was never chosen. So the default is a defensive mixture:
//   half by power, half uniform over light objects (a Blender lamp, or all emissive triangles
//   of one object, chosen within the object by power):
//       p(j) = ½ Φ_j / ΣΦ + ½ (1/G) Φ_j / Φ_g(j),   G objects, Φ_g the power of j's object.
// * tree: the light tree (lights/light_tree.h) over the finite lights, its probabilities
//   depending on the shading point (p, n); the lights at infinity (sun, environment: no
//   bounds()) stay outside it and are chosen as pbrt-v4's BVHLightSampler does, each with
//       p_inf = 1 / (N_inf + 1)   (1 / N_inf when the tree is empty),
//   the tree with the rest, 1 − N_inf p_inf. Light tracing has no shading point to choose for:
//   its emission (sample_emission) chooses by power under `tree`. The tree, and the split into
//   lights at infinity and the rest (every light's bounds()), are made on first use: a render
//   with another mode never pays for them.
// * auto (the default): tree when the scene holds more than kAutoTreeLights = 3 light entries
//   (lamps, suns, the environment, emissive triangles), else mixed. Measured at equal time
//   (scripts/study/auto_lights.py, docs/study.md "Light selection"; MSE x seconds of tree over
//   mixed): 1 lamp 1.03-1.07 (the descent's cost, nothing to gain), 2 lamps 0.58 scattered but
//   1.02 in a tight cluster, 4 lamps 0.14 scattered and 0.71 clustered, 8-64 lamps 0.11-0.73.
// * tree with splitting (light_tree_splits = max_cut > 1, lights/light_tree.h): the tree's
//   share is one sub-estimator per node of the cut at p, each choosing a light below its node;
//   sample_cut() returns one light sample per node, each with pdf share × (its probability
//   below the node) × the light's point pdf, and NEE sums them. A light's probability for MIS
//   is that same product (probability(), lamp_radiance(), emissive_triangle_pdf() with
//   max_cut). Sub-estimator c takes the vertex's choice number and point rotated by c times
//   the R2 sequence's offsets (Roberts 2018: 1/φ for the choice, 1/ψ, 1/ψ² for the point; c = 0
//   unrotated), mod 1: a rotation mod 1 keeps each uniform, so each sub-estimator stays
//   unbiased, and the sub-estimators' choices are decorrelated without new sampler dimensions
//   (which would move every later dimension and change every image with splitting off).
// Any p > 0 wherever a light contributes keeps NEE unbiased; a zero total power makes the
// power choice uniform.
#pragma once

#include <array>
#include <atomic>
#include <concepts>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

#include "lights/emissive_triangle.h"
#include "lights/environment_light.h"
#include "lights/lamp_bvh.h"
#include "lights/lamp_program.h"
#include "lights/light.h"
#include "lights/light_selection.h"
#include "lights/light_tree.h"
#include "lights/world_program.h"
#include "scene/light_links.h"

namespace stratum {

// Which emitters (lamps, emissive surfaces) a forward ray may find under light and shadow
// linking (scene/light_links.h). Camera rays (inactive filter) see every emitter; another ray
// only emitters that light the receiver set of its last scattering vertex and are not
// shadow-linked (those it finds through the dedicated pass, integrators/shadow_linking.h).
struct EmitterLinkFilter {
    bool active = false;
    uint8_t receiver_set = 0;
    bool accepts(const LightLinks& emitter) const {
        return !active || (emitter.lights(receiver_set) && !emitter.shadow_linked());
    }
};

class LightSet {
public:
    // `auto` chooses the tree above this many light entries (header; the measurement behind it
    // is in docs/study.md "Light selection").
    static constexpr size_t kAutoTreeLights = 3;

    // `object` groups lights that belong to one scene object (the triangles of one emissive
    // mesh); every Blender lamp is an object of its own. `visibility` (StratumVisibility bits)
    // is copied into every LightSample of the light. `links`: the object's memberships as an
    // emitter (scene/light_links.h; the same for every light of one object). Returns the index
    // of the added light.
    uint32_t add(std::unique_ptr<const Light> light, uint32_t object, uint32_t visibility = kVisibleAll,
                 const LightLinks& links = {});
    template <std::derived_from<Light> L>
    uint32_t add(L light, uint32_t object, uint32_t visibility = kVisibleAll, const LightLinks& links = {}) {
        static_assert(!std::same_as<L, EnvironmentLight>, "the environment goes through add_environment");
        return add(std::make_unique<const L>(std::move(light)), object, visibility, links);
    }
    // The environment (at most one): a light like the others, which background() also looks up.
    uint32_t add_environment(EnvironmentLight environment, uint32_t object);
    // Scales light `index`'s emission by `program` (a lamp's node tree, lights/lamp_program.h)
    // wherever sample(), sample_cut(), lamp_radiance() and sample_emission() give it. power()
    // stays the light's own: a program moves no choice among lights (never biased, at worst
    // noisier where it brightens a lamp).
    void set_program(uint32_t index, std::shared_ptr<const LampProgram> program);
    // The environment's values from the world's program (lights/world_program.h), which reads
    // the Light Path node: sample() and sample_cut() give its radiance for their `path`, the map
    // only chooses directions. Set after add_environment.
    void set_world_program(std::shared_ptr<const WorldProgram> program) {
        world_program_ = std::move(program);
    }
    const WorldProgram* world_program() const { return world_program_.get(); }
    // Puts light `index` in light group `group` (0 = none, the default): LightSample::lightgroup and
    // lamp_radiance's *lightgroup give it (film/light_groups.h).
    void set_lightgroup(uint32_t index, uint32_t group) { lightgroup_[index] = group; }
    uint32_t lightgroup(uint32_t index) const { return lightgroup_[index]; }
    // scene_radius: radius of a sphere bounding the scene, to give the sun and the environment a
    // power.
    void finalize(float scene_radius);
    // Light linking: the finalized set of the lights that light receiver set `receiver_set`
    // (every light of this one whose links light it: lamps, triangles, the environment), with
    // their objects, visibility, links and programs, sharing the light models. NEE at a surface
    // of that set chooses among these only (Cycles builds a light tree per receiver set): a
    // receiver lit by few of many lights does not spend its samples on the others. *index_of
    // (this set's size) gets each light's index in the subset, or kNoLightIndex.
    LightSet lighting(uint8_t receiver_set, std::vector<uint32_t>* index_of) const;
    static constexpr uint32_t kNoLightIndex = 0xffffffffu;

    bool empty() const { return lights_.empty(); }
    size_t size() const { return lights_.size(); }
    const Light& light(uint32_t index) const { return *lights_[index]; }
    // The mode `selection` stands for in this scene: auto's choice (header), the others as they are.
    LightSelection resolve(LightSelection selection) const {
        return selection != LightSelection::Auto
                   ? selection
                   : (lights_.size() > kAutoTreeLights ? LightSelection::Tree : LightSelection::Mixed);
    }
    uint32_t visibility(uint32_t index) const { return visibility_[index]; }
    // Light `index`'s memberships as an emitter (scene/light_links.h); the world has none.
    const LightLinks& links(uint32_t index) const { return object_links_[object_[index]]; }
    // Whether some light lights only some receivers, or has its shadows cast by some occluders
    // only (is shadow-linked).
    bool has_light_linking() const { return has_light_linking_; }
    bool has_shadow_linking() const { return has_shadow_linking_; }
    // The shadow sets whose occluders block every shadow-linked light (their memberships' AND):
    // past an opaque one of these no shadow-linked light can be seen (integrators/shadow_linking.h).
    uint64_t shadow_sets_blocking_all_linked() const { return blocking_all_linked_; }
    // Power Φ_j of light `index` (W; the sun's and the environment's through the scene's
    // cross-section), as the selection distributions use it.
    double power(uint32_t index) const { return power_[index]; }
    // The probability with which `selection` chooses light `index` without a shading point:
    // the tree's emission choice is by power (header).
    float probability(uint32_t index, LightSelection selection = LightSelection::Mixed) const {
        return probability_[static_table(selection)][index];
    }
    // The probability with which `selection` chooses light `index` for the shading point p of
    // normal n (unit, or 0): the tree's, or the table above for the other modes.
    float probability(uint32_t index, Vec3 p, Vec3 n, LightSelection selection, uint32_t max_cut = 1) const;
    // The light `selection` chooses for u in [0,1) without a shading point (the tree's emission
    // choice is by power); size() when there are no lights.
    uint32_t choose(float u, LightSelection selection = LightSelection::Mixed) const;
    // The light `selection` chooses for u in [0,1) at (p, n), and its probability (*choice);
    // size() (choice 0) when there is none.
    uint32_t choose(float u, Vec3 p, Vec3 n, LightSelection selection, float* choice) const;
    // The light tree over the finite lights, built on first use (thread-safe, deterministic).
    const LightTree& tree() const;
    // What building the tree cost: seconds (with every light's bounds()) and bytes held.
    struct TreeReport {
        double seconds = 0.0;
        size_t bytes = 0;
    };
    // The report once tree() has been built, else nullopt; never builds it (a progress query
    // from another thread may call it while a render builds the tree).
    std::optional<TreeReport> tree_report() const;
    // Chooses a light with u_choice and samples it with u for the shading point p of normal n
    // (unit; 0 when it has none); out->pdf includes the choice. `triangle` is how a point on a
    // chosen emissive triangle is taken (n shapes it: lights/emissive_triangle.h).
    // `path`: the Light Path inputs the lamps' and the world's programs see (the light sample's:
    // LightPathState::emission of the shading point's path).
    bool sample(Vec3 p, Vec3 n, float u_choice, Vec2 u, LightSample* out,
                LightSelection selection = LightSelection::Mixed,
                TriangleSampling triangle = TriangleSampling::SolidAngle,
                const LightPathState& path = kDirectLightPath) const;
    // sample() with the tree's splitting (header): up to LightTree::kMaxCut light samples into
    // out[], one per cut node whose light was sampled; returns their count. Exactly sample()
    // when max_cut is 1 or `selection` is not the tree.
    uint32_t sample_cut(Vec3 p, Vec3 n, float u_choice, Vec2 u, LightSample* out, LightSelection selection,
                        TriangleSampling triangle, uint32_t max_cut,
                        const LightPathState& path = kDirectLightPath) const;
    // Light tracing: chooses a light with u_choice by `selection` and emits a particle from it
    // (the lights' sample_emission); out->weight is divided by the choice probability, so it
    // estimates the scene's total emitted flux. The sun and the environment shine over the
    // scene's bounding sphere (center, radius). False when the chosen light emits nothing.
    bool sample_emission(float u_choice, Vec2 u_position, Vec2 u_direction, LightSelection selection,
                         Vec3 center, float radius, EmissionSample* out) const;
    // Pdf (choice × solid angle) with which sample() at (p, n) reaches `hit` on emissive
    // triangle `index` (a SurfaceHit's emissive_light: always an EmissiveTriangle).
    float emissive_triangle_pdf(uint32_t index, Vec3 p, Vec3 n, Vec3 hit,
                                LightSelection selection = LightSelection::Mixed,
                                TriangleSampling triangle = TriangleSampling::SolidAngle,
                                uint32_t max_cut = 1) const;
    // Radiance of the nearest lamp surface (an area lamp, or the disk of a point/spot lamp with
    // a radius, facing the ray's origin) whose visibility has bit `visibility` and whose
    // emitting face the ray (dir unit) meets before t_max; black if none. Lamps are not in the
    // BVH: this is how camera rays (Cycles' Object > Visibility > Camera on a light) and
    // BSDF-scattered rays find them. *pdf (if not null) = the pdf (choice × solid angle) with
    // which sample() at `origin` picks that direction, for MIS; under `tree` the choice is the
    // one at (choice_point, choice_normal), the vertex whose NEE the pdf is compared with.
    // *t (if not null) = the distance to the lamp; *lightgroup (if not null) = its light group.
    // `path`: the Light Path inputs the lamp's program sees (LightPathState::emission); `link`:
    // the lamps a forward ray may find under light and shadow linking (EmitterLinkFilter); the
    // others are passed through.
    Rgb lamp_radiance(Vec3 origin, Vec3 dir, float t_max, uint32_t visibility, float* pdf = nullptr,
                      float* t = nullptr, LightSelection selection = LightSelection::Mixed,
                      Vec3 choice_point = {}, Vec3 choice_normal = {}, uint32_t max_cut = 1,
                      const LightPathState& path = kDirectLightPath, const EmitterLinkFilter& link = {},
                      uint32_t* lightgroup = nullptr) const;
    // Calls f(index, t, radiance, solid_angle_pdf) for every lamp with visibility bit
    // `visibility` whose emitting face the ray (dir unit) meets before t_max, in no set order;
    // radiance includes the lamp's program (seeing `path`), solid_angle_pdf is Light::intersect's.
    template <typename F>
    void visit_lamp_hits(Vec3 origin, Vec3 dir, float t_max, uint32_t visibility, const LightPathState& path,
                         F&& f) const {
        lamp_bvh_.visit(origin, dir, t_max, [&](uint32_t item) {
            const uint32_t i = hittable_lamps_[item];
            if (!(visibility_[i] & visibility)) return;
            float t, solid_angle_pdf;
            Rgb L;
            if (!lights_[i]->intersect(origin, dir, t_max, &t, &L, &solid_angle_pdf)) return;
            f(i, t, programs_[i] ? L * programs_[i]->scale(t, path) : L, solid_angle_pdf);
        });
    }
    // The environment (at most one), or null; its pdf (choice × solid angle) for direction wi.
    // No shading point is needed: under `tree` a light at infinity has the fixed p_inf.
    const EnvironmentLight* environment() const { return environment_; }
    float environment_pdf(Vec3 wi, LightSelection selection = LightSelection::Mixed) const;
    // Whether some light can be reached only by light sampling: a point or spot lamp of radius
    // 0 or a sun of angle 0 (delta lights no scattered ray finds).
    bool has_delta_lights() const { return delta_lights_ > 0; }
    uint32_t delta_light_count() const { return delta_lights_; }

private:
    // Shared with the sets lighting() makes.
    std::vector<std::shared_ptr<const Light>> lights_;
    uint32_t add_shared(std::shared_ptr<const Light> light, uint32_t object, uint32_t visibility,
                        const LightLinks& links);
    float scene_radius_ = 1.0f;
    std::vector<uint32_t> object_;          // object of each light
    std::vector<uint32_t> visibility_;      // StratumVisibility bits of each light
    std::vector<LightLinks> object_links_;  // of each light object
    bool has_light_linking_ = false, has_shadow_linking_ = false;
    uint64_t blocking_all_linked_ = kAllLinkSets;
    std::vector<uint32_t> lightgroup_;                          // light group of each light (0 none)
    std::vector<std::shared_ptr<const LampProgram>> programs_;  // of each light, or null
    std::shared_ptr<const WorldProgram> world_program_;         // of the environment, or null
    std::vector<uint32_t> hittable_lamps_;  // lamps with a surface rays meet (lamp_radiance)
    LampBvh lamp_bvh_;                      // over hittable_lamps_ (its items number them)
    std::vector<double> power_;             // Φ_j, set by finalize()
    // The table a mode chooses by without a shading point: its own, power's for the tree.
    size_t static_table(LightSelection selection) const {
        selection = resolve(selection);
        return static_cast<size_t>(selection == LightSelection::Tree ? LightSelection::Power : selection);
    }
    // Per static LightSelection: cdf[i] = P(choice < i+1) (last = 1), and the choice probabilities.
    std::array<std::vector<float>, kStaticLightSelectionModes> cdf_, probability_;
    // Made by tree_state() on first use; a unique_ptr so that LightSet stays movable.
    struct TreeCache {
        std::once_flag once;
        std::unique_ptr<const LightTree> tree;
        // Lights at infinity (no bounds()), each chosen by the tree mode with infinite_probability.
        std::vector<uint32_t> infinite;
        std::vector<uint8_t> is_infinite;
        float infinite_probability = 0.0f;
        bool tree_has_lights = false;
        TreeReport report;
        std::atomic<bool> built{false};  // report is complete (release/acquire)
    };
    const TreeCache& tree_state() const;
    std::unique_ptr<TreeCache> tree_cache_ = std::make_unique<TreeCache>();
    uint32_t delta_lights_ = 0;
    const EnvironmentLight* environment_ = nullptr;  // owned by lights_
    uint32_t environment_index_ = 0;
};

}  // namespace stratum
