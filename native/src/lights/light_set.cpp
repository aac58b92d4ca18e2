#include "lights/light_set.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <unordered_map>

namespace stratum {

uint32_t LightSet::add(std::unique_ptr<const Light> light, uint32_t object, uint32_t visibility,
                       const LightLinks& links) {
    return add_shared(std::move(light), object, visibility, links);
}

uint32_t LightSet::add_shared(std::shared_ptr<const Light> light, uint32_t object, uint32_t visibility,
                              const LightLinks& links) {
    const auto index = static_cast<uint32_t>(lights_.size());
    if (object >= object_links_.size()) object_links_.resize(object + 1);
    object_links_[object] = links;
    has_light_linking_ = has_light_linking_ || links.light_set_membership != kAllLinkSets;
    if (links.shadow_linked()) {
        has_shadow_linking_ = true;
        blocking_all_linked_ &= links.shadow_set_membership;
    }
    if (light->is_hittable_lamp()) hittable_lamps_.push_back(index);
    if (light->is_delta()) ++delta_lights_;
    lights_.push_back(std::move(light));
    object_.push_back(object);
    visibility_.push_back(visibility);
    lightgroup_.push_back(0);
    programs_.push_back(nullptr);
    return index;
}

void LightSet::set_program(uint32_t index, std::shared_ptr<const LampProgram> program) {
    programs_[index] = std::move(program);
}

uint32_t LightSet::add_environment(EnvironmentLight environment, uint32_t object) {
    auto light = std::make_unique<const EnvironmentLight>(std::move(environment));
    environment_ = light.get();
    // The world lights everything, the catcher-only copy of a camera path too (Cycles 5.0 forces
    // its light's is_shadow_catcher; in 3.4 the background light keeps the default, true).
    environment_index_ = add(std::move(light), object, trace_visibility(kVisibleAll | kVisibleShadowCatcher));
    return environment_index_;
}

LightSet LightSet::lighting(uint8_t receiver_set, std::vector<uint32_t>* index_of) const {
    LightSet subset;
    index_of->assign(lights_.size(), kNoLightIndex);
    for (uint32_t i = 0; i < lights_.size(); ++i) {
        if (!links(i).lights(receiver_set)) continue;
        const uint32_t k = subset.add_shared(lights_[i], object_[i], visibility_[i], links(i));
        subset.programs_[k] = programs_[i];
        subset.lightgroup_[k] = lightgroup_[i];
        if (environment_ && i == environment_index_) {
            subset.environment_ = environment_;
            subset.environment_index_ = k;
            subset.world_program_ = world_program_;
        }
        (*index_of)[i] = k;
    }
    subset.finalize(scene_radius_);
    return subset;
}

void LightSet::finalize(float scene_radius) {
    scene_radius_ = scene_radius;
    std::vector<double> power(lights_.size());
    for (size_t i = 0; i < lights_.size(); ++i) power[i] = lights_[i]->power(scene_radius);
    power_ = power;
    double total = 0.0;
    std::unordered_map<uint32_t, double> object_power;
    for (size_t i = 0; i < lights_.size(); ++i) {
        total += power[i];
        object_power[object_[i]] += power[i];
    }
    std::unordered_map<uint32_t, size_t> object_size;
    for (uint32_t o : object_) ++object_size[o];
    const double objects = static_cast<double>(object_power.size());
    const double uniform = 1.0 / static_cast<double>(std::max<size_t>(1, lights_.size()));
    for (uint32_t mode = 0; mode < kStaticLightSelectionModes; ++mode) {
        probability_[mode].resize(lights_.size());
        cdf_[mode].resize(lights_.size());
        double running = 0.0;
        for (size_t i = 0; i < lights_.size(); ++i) {
            // Zero total (or object) power: the power-proportional part is uniform instead.
            const double by_power = total > 0.0 ? power[i] / total : uniform;
            double p = uniform;
            switch (static_cast<LightSelection>(mode)) {
                case LightSelection::Mixed: {
                    const double in_object = object_power[object_[i]] > 0.0
                                                 ? power[i] / object_power[object_[i]]
                                                 : 1.0 / static_cast<double>(object_size[object_[i]]);
                    p = 0.5 * by_power + 0.5 * in_object / objects;
                    break;
                }
                // The tree's choice without a shading point (emission) is power's table; auto
                // is resolved to tree or mixed before a table is read (static_table).
                case LightSelection::Power:
                case LightSelection::Tree:
                case LightSelection::Auto:
                    p = by_power;
                    break;
                case LightSelection::Uniform:
                    break;
            }
            probability_[mode][i] = static_cast<float>(p);
            running += p;
            cdf_[mode][i] = static_cast<float>(running);
        }
        if (!cdf_[mode].empty()) cdf_[mode].back() = 1.0f;
    }
    // Boxes of the lamps rays meet, for lamp_radiance. A lamp that gives no bounds() gets the
    // whole space (tested by every ray, as before the hierarchy).
    std::vector<LampBvh::Box> boxes;
    boxes.reserve(hittable_lamps_.size());
    constexpr float kEverywhere = 0.25f * std::numeric_limits<float>::max();
    for (const uint32_t i : hittable_lamps_) {
        const std::optional<LightBounds> b = lights_[i]->bounds();
        boxes.push_back(b ? LampBvh::Box{b->lo, b->hi}
                          : LampBvh::Box{Vec3(-kEverywhere, -kEverywhere, -kEverywhere),
                                         Vec3(kEverywhere, kEverywhere, kEverywhere)});
    }
    lamp_bvh_ = LampBvh(boxes);
    tree_cache_ = std::make_unique<TreeCache>();
}

const LightSet::TreeCache& LightSet::tree_state() const {
    std::call_once(tree_cache_->once, [this] {
        const auto start = std::chrono::steady_clock::now();
        TreeCache& cache = *tree_cache_;
        // The split between the lights at infinity and the tree (header).
        cache.is_infinite.assign(lights_.size(), 0);
        std::vector<LightBounds> bounds;
        std::vector<uint32_t> index;
        for (size_t i = 0; i < lights_.size(); ++i) {
            std::optional<LightBounds> b = lights_[i]->bounds();
            if (!b) {
                cache.infinite.push_back(static_cast<uint32_t>(i));
                cache.is_infinite[i] = 1;
                continue;
            }
            cache.tree_has_lights = cache.tree_has_lights || power_[i] > 0.0;
            b->phi = power_[i];
            bounds.push_back(*b);
            index.push_back(static_cast<uint32_t>(i));
        }
        const size_t choices = cache.infinite.size() + (cache.tree_has_lights ? 1 : 0);
        cache.infinite_probability = choices > 0 ? 1.0f / static_cast<float>(choices) : 0.0f;
        cache.tree = std::make_unique<const LightTree>(bounds, index);
        cache.report.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        cache.report.bytes = cache.tree->memory_bytes() + cache.infinite.capacity() * sizeof(uint32_t) +
                             cache.is_infinite.capacity();
        cache.built.store(true, std::memory_order_release);
    });
    return *tree_cache_;
}

const LightTree& LightSet::tree() const { return *tree_state().tree; }

std::optional<LightSet::TreeReport> LightSet::tree_report() const {
    if (!tree_cache_->built.load(std::memory_order_acquire)) return std::nullopt;
    return tree_cache_->report;
}

float LightSet::probability(uint32_t index, Vec3 p, Vec3 n, LightSelection selection,
                            uint32_t max_cut) const {
    if (resolve(selection) != LightSelection::Tree) return probability(index, selection);
    const TreeCache& state = tree_state();
    if (state.is_infinite[index]) return state.infinite_probability;
    // The tree's share, 1 − N_inf p_inf, as choose() forms it.
    const float share = 1.0f - static_cast<float>(state.infinite.size()) * state.infinite_probability;
    return share * state.tree->pmf(p, n, index, max_cut);
}

uint32_t LightSet::choose(float u, Vec3 p, Vec3 n, LightSelection selection, float* choice) const {
    if (resolve(selection) != LightSelection::Tree) {
        const uint32_t index = choose(u, selection);
        *choice = lights_.empty() ? 0.0f : probability(index, selection);
        return lights_.empty() ? static_cast<uint32_t>(lights_.size()) : index;
    }
    *choice = 0.0f;
    const auto none = static_cast<uint32_t>(lights_.size());
    if (lights_.empty()) return none;
    const TreeCache& state = tree_state();
    const float infinite_total = static_cast<float>(state.infinite.size()) * state.infinite_probability;
    if (u < infinite_total) {
        const auto k =
            std::min(static_cast<size_t>(u / state.infinite_probability), state.infinite.size() - 1);
        *choice = state.infinite_probability;
        return state.infinite[k];
    }
    if (!state.tree_has_lights) return none;
    const float share = 1.0f - infinite_total;
    const float u_tree = std::min((u - infinite_total) / share, kOneMinusEpsilon);
    float pmf = 0.0f;
    const uint32_t index = state.tree->choose(p, n, u_tree, &pmf);
    if (index == LightTree::kNone) return none;
    *choice = share * pmf;
    return index;
}

uint32_t LightSet::choose(float u, LightSelection selection) const {
    if (lights_.empty()) return 0;
    const std::vector<float>& cdf = cdf_[static_table(selection)];
    const auto it = std::upper_bound(cdf.begin(), cdf.end(), u);
    return static_cast<uint32_t>(std::min(static_cast<size_t>(it - cdf.begin()), lights_.size() - 1));
}

bool LightSet::sample(Vec3 p, Vec3 n, float u_choice, Vec2 u, LightSample* out, LightSelection selection,
                      TriangleSampling triangle, const LightPathState& path) const {
    if (lights_.empty()) return false;
    float choice = 0.0f;
    const uint32_t index = choose(u_choice, p, n, selection, &choice);
    if (!(choice > 0.0f)) return false;
    if (!lights_[index]->sample(p, n, u, triangle, out)) return false;
    out->pdf *= choice;
    out->visibility = visibility_[index];
    out->light = index;
    out->lightgroup = lightgroup_[index];
    if (programs_[index]) out->radiance = out->radiance * programs_[index]->scale(out->distance, path);
    if (world_program_ && index == environment_index_)
        out->radiance = world_program_->radiance(out->wi, path);
    return true;
}

uint32_t LightSet::sample_cut(Vec3 p, Vec3 n, float u_choice, Vec2 u, LightSample* out,
                              LightSelection selection, TriangleSampling triangle, uint32_t max_cut,
                              const LightPathState& path) const {
    if (max_cut <= 1 || resolve(selection) != LightSelection::Tree)
        return sample(p, n, u_choice, u, out, selection, triangle, path) ? 1u : 0u;
    if (lights_.empty()) return 0;
    const TreeCache& state = tree_state();
    const float infinite_total = static_cast<float>(state.infinite.size()) * state.infinite_probability;
    // A light at infinity is one choice as in choose(); the tree's share is split.
    if (u_choice < infinite_total) return sample(p, n, u_choice, u, out, selection, triangle, path) ? 1u : 0u;
    if (!state.tree_has_lights) return 0;
    const float share = 1.0f - infinite_total;
    const float u_tree = std::min((u_choice - infinite_total) / share, kOneMinusEpsilon);
    LightTree::Cut cut;
    state.tree->cut(p, n, max_cut, &cut);
    // The R2 sequence's offsets (header): 1/φ, and 1/ψ, 1/ψ² with ψ³ = ψ + 1.
    constexpr float kChoiceStep = 0.6180339887f, kPointStep[2] = {0.7548776662f, 0.5698402910f};
    const auto rotate = [](float v, float offset) {
        const float r = v + offset;
        return std::min(r >= 1.0f ? r - 1.0f : r, kOneMinusEpsilon);
    };
    uint32_t count = 0;
    for (uint32_t c = 0; c < cut.size; ++c) {
        // c × offset mod 1, so that the rotation stays in [0, 1) for every c.
        const auto step = [c](float offset) {
            const float total = static_cast<float>(c) * offset;
            return total - std::floor(total);
        };
        const float u_c = c == 0 ? u_tree : rotate(u_tree, step(kChoiceStep));
        const Vec2 u_point =
            c == 0 ? u : Vec2{rotate(u.x, step(kPointStep[0])), rotate(u.y, step(kPointStep[1]))};
        float pmf = 0.0f;
        const uint32_t index = state.tree->choose_in_cut(cut.node[c], p, n, u_c, &pmf);
        if (index == LightTree::kNone || !(pmf > 0.0f)) continue;
        LightSample& ls = out[count];
        if (!lights_[index]->sample(p, n, u_point, triangle, &ls)) continue;
        ls.pdf *= share * pmf;
        ls.visibility = visibility_[index];
        ls.light = index;
        ls.lightgroup = lightgroup_[index];
        if (programs_[index]) ls.radiance = ls.radiance * programs_[index]->scale(ls.distance, path);
        ++count;
    }
    return count;
}

float LightSet::emissive_triangle_pdf(uint32_t index, Vec3 p, Vec3 n, Vec3 hit, LightSelection selection,
                                      TriangleSampling triangle, uint32_t max_cut) const {
    const auto& tri = static_cast<const EmissiveTriangle&>(*lights_[index]);
    return probability(index, p, n, selection, max_cut) * tri.pdf(p, n, hit, triangle);
}

Rgb LightSet::lamp_radiance(Vec3 origin, Vec3 dir, float t_max, uint32_t visibility, float* pdf, float* t_out,
                            LightSelection selection, Vec3 choice_point, Vec3 choice_normal, uint32_t max_cut,
                            const LightPathState& path, const EmitterLinkFilter& link,
                            uint32_t* lightgroup) const {
    uint32_t nearest_lamp = 0;
    bool found = false;
    Rgb radiance(0.0f);
    float nearest = t_max, nearest_pdf = 0.0f;
    // The lamps whose boxes the ray crosses before the nearest hit so far. The result is the
    // one a loop over all lamps in index order finds: the nearest (t < t_max), and of lamps at
    // the same distance the first by index (so a tie is met again at t = nearest, inclusive).
    lamp_bvh_.visit(origin, dir, nearest, [&](uint32_t item) {
        const uint32_t i = hittable_lamps_[item];
        if (!(visibility_[i] & visibility) || !link.accepts(links(i))) return;
        const float limit = found ? std::nextafter(nearest, std::numeric_limits<float>::infinity()) : nearest;
        float t, solid_angle_pdf;
        Rgb L;
        if (lights_[i]->intersect(origin, dir, limit, &t, &L, &solid_angle_pdf) &&
            (!found || t < nearest || i < nearest_lamp)) {
            nearest = t;
            radiance = L;
            nearest_pdf = solid_angle_pdf;
            nearest_lamp = i;
            found = true;
        }
    });
    // The choice probability of the nearest lamp only (the tree's costs a descent).
    if (pdf)
        *pdf = found
                   ? probability(nearest_lamp, choice_point, choice_normal, selection, max_cut) * nearest_pdf
                   : 0.0f;
    if (t_out) *t_out = nearest;
    if (lightgroup) *lightgroup = found ? lightgroup_[nearest_lamp] : 0;
    if (found && programs_[nearest_lamp]) radiance = radiance * programs_[nearest_lamp]->scale(nearest, path);
    return radiance;
}

float LightSet::environment_pdf(Vec3 wi, LightSelection selection) const {
    if (!environment_) return 0.0f;
    const float choice = resolve(selection) == LightSelection::Tree
                             ? tree_state().infinite_probability
                             : probability(environment_index_, selection);
    return choice * environment_->pdf(wi);
}

bool LightSet::sample_emission(float u_choice, Vec2 u_position, Vec2 u_direction, LightSelection selection,
                               Vec3 center, float radius, EmissionSample* out) const {
    if (lights_.empty()) return false;
    const uint32_t index = choose(u_choice, selection);
    const float choice = probability(index, selection);
    if (!(choice > 0.0f)) return false;
    if (!lights_[index]->sample_emission(u_position, u_direction, center, radius, out)) return false;
    if (out->weight.is_black()) return false;
    out->weight = out->weight * (1.0f / choice);
    out->visibility = visibility_[index];
    out->program = programs_[index].get();
    return true;
}

}  // namespace stratum
