#include "lights/light_tree.h"

#include <algorithm>
#include <array>
#include <limits>

namespace stratum {

LightTree::LightTree(const std::vector<LightBounds>& bounds, const std::vector<uint32_t>& light) {
    std::vector<Item> items;
    uint32_t lights = 0;
    double total_phi = 0.0;
    for (size_t i = 0; i < bounds.size(); ++i) {
        lights = std::max(lights, light[i] + 1);
        if (bounds[i].phi > 0.0) {
            items.push_back({bounds[i], light[i]});
            total_phi += bounds[i].phi;
        }
    }
    trails_.resize(lights);
    if (items.empty()) return;
    const double phi_scale = 1.0 / total_phi;
    if (items.size() == 1) {
        has_single_ = true;
        single_.set(0, items[0].bounds, phi_scale, items[0].light, true);
        trails_[items[0].light] = {0, 0, true};
        return;
    }
    pairs_.reserve(items.size() - 1);
    build(items, 0, items.size(), 0, 0, phi_scale);
}

LightBounds LightTree::build(std::vector<Item>& items, size_t begin, size_t end, uint64_t bits,
                             uint32_t depth, double phi_scale) {
    const auto index = static_cast<uint32_t>(pairs_.size());
    pairs_.emplace_back();
    Vec3 centre_lo = items[begin].bounds.centre(), centre_hi = centre_lo;
    LightBounds all = items[begin].bounds;
    for (size_t i = begin + 1; i < end; ++i) {
        centre_lo = component_min(centre_lo, items[i].bounds.centre());
        centre_hi = component_max(centre_hi, items[i].bounds.centre());
        all = merge(all, items[i].bounds);
    }
    // The cheapest bucket boundary over the three axes (the header's cost).
    int best_axis = -1, best_split = 0;
    double best_cost = std::numeric_limits<double>::infinity();
    const auto bucket_of = [&](const Item& item, int axis) {
        const float extent = centre_hi[axis] - centre_lo[axis];
        const auto b = static_cast<int>(kBuckets * ((item.bounds.centre()[axis] - centre_lo[axis]) / extent));
        return std::clamp(b, 0, kBuckets - 1);
    };
    const Vec3 centre_extent = centre_hi - centre_lo;
    const float min_extent = std::max({centre_extent.x, centre_extent.y, centre_extent.z}) / kBuckets;
    if (depth < kMedianDepth) {
        for (int axis = 0; axis < 3; ++axis) {
            if (!(centre_hi[axis] > centre_lo[axis])) continue;
            std::array<LightBounds, kBuckets> bucket{};
            std::array<bool, kBuckets> filled{};
            for (size_t i = begin; i < end; ++i) {
                const int b = bucket_of(items[i], axis);
                bucket[b] = filled[b] ? merge(bucket[b], items[i].bounds) : items[i].bounds;
                filled[b] = true;
            }
            // Sweeps from both ends: below[s] holds buckets [0, s), above[s] buckets [s, kBuckets).
            std::array<LightBounds, kBuckets + 1> below{}, above{};
            std::array<bool, kBuckets + 1> any_below{}, any_above{};
            for (int b = 0; b < kBuckets; ++b) {
                below[b + 1] =
                    !filled[b] ? below[b] : (any_below[b] ? merge(below[b], bucket[b]) : bucket[b]);
                any_below[b + 1] = any_below[b] || filled[b];
            }
            for (int b = kBuckets - 1; b >= 0; --b) {
                above[b] = !filled[b] ? above[b + 1]
                                      : (any_above[b + 1] ? merge(above[b + 1], bucket[b]) : bucket[b]);
                any_above[b] = any_above[b + 1] || filled[b];
            }
            for (int split = 1; split < kBuckets; ++split) {
                if (!any_below[split] || !any_above[split]) continue;
                const double cost =
                    split_cost(below[split], axis, min_extent) + split_cost(above[split], axis, min_extent);
                if (cost < best_cost) {
                    best_cost = cost;
                    best_axis = axis;
                    best_split = split;
                }
            }
        }
    }
    const auto first = items.begin() + static_cast<std::ptrdiff_t>(begin);
    const auto last = items.begin() + static_cast<std::ptrdiff_t>(end);
    auto middle = first + static_cast<std::ptrdiff_t>((end - begin) / 2);
    if (best_axis >= 0) {
        middle = std::partition(first, last,
                                [&](const Item& item) { return bucket_of(item, best_axis) < best_split; });
    } else {
        // Deep, or every centroid at one point: halves by count along the widest centroid axis,
        // ties broken by the light's index so the build is deterministic.
        const Vec3 extent = centre_hi - centre_lo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        std::nth_element(first, middle, last, [axis](const Item& a, const Item& b) {
            const float ca = a.bounds.centre()[axis], cb = b.bounds.centre()[axis];
            return ca < cb || (ca == cb && a.light < b.light);
        });
    }
    const size_t split = static_cast<size_t>(middle - items.begin());
    const std::array<size_t, 3> range{begin, split, end};
    for (int k = 0; k < 2; ++k) {
        const uint64_t child_bits = bits | (static_cast<uint64_t>(k) << depth);
        if (range[k + 1] - range[k] == 1) {
            const Item& item = items[range[k]];
            pairs_[index].set(k, item.bounds, phi_scale, item.light, true);
            trails_[item.light] = {child_bits, depth + 1, true};
            depth_ = std::max(depth_, depth + 1);
        } else {
            const auto child = static_cast<uint32_t>(pairs_.size());
            const LightBounds bound = build(items, range[k], range[k + 1], child_bits, depth + 1, phi_scale);
            pairs_[index].set(k, bound, phi_scale, child, false);
        }
    }
    return all;
}

float LightTree::first_child_probability(uint32_t pair, Vec3 p, Vec3 n, bool has_normal) const {
    const ImportancePair& children = pairs_[pair];
    const float i0 = importance(children, 0, p, n, has_normal);
    const float i1 = importance(children, 1, p, n, has_normal);
    if (!(i0 + i1 > 0.0f)) return -1.0f;
    return i0 / (i0 + i1);
}

uint32_t LightTree::choose(Vec3 p, Vec3 n, float u, float* pmf) const {
    *pmf = 0.0f;
    const bool has_normal = dot(n, n) > 0.0f;
    // A tree of one light takes it wherever it can contribute.
    if (has_single_) {
        if (!(importance(single_, 0, p, n, has_normal) > 0.0f)) return kNone;
        *pmf = 1.0f;
        return single_.child[0];
    }
    if (pairs_.empty()) return kNone;
    float probability = 1.0f;
    uint32_t pair = 0;
    for (;;) {
        const float p0 = first_child_probability(pair, p, n, has_normal);
        if (p0 < 0.0f) return kNone;
        int k = 0;
        if (u < p0) {
            u = std::min(u / p0, kOneMinusEpsilon);
            probability *= p0;
        } else {
            u = std::min((u - p0) / (1.0f - p0), kOneMinusEpsilon);
            probability *= 1.0f - p0;
            k = 1;
        }
        if (pairs_[pair].leaf(k)) {
            *pmf = probability;
            return pairs_[pair].child[k];
        }
        pair = pairs_[pair].child[k];
    }
}

float LightTree::pmf(Vec3 p, Vec3 n, uint32_t light) const {
    if (light >= trails_.size() || !trails_[light].in_tree) return 0.0f;
    const bool has_normal = dot(n, n) > 0.0f;
    if (has_single_) return importance(single_, 0, p, n, has_normal) > 0.0f ? 1.0f : 0.0f;
    const Trail& trail = trails_[light];
    float probability = 1.0f;
    uint32_t pair = 0;
    for (uint32_t level = 0; level < trail.depth; ++level) {
        const float p0 = first_child_probability(pair, p, n, has_normal);
        if (p0 < 0.0f) return 0.0f;
        const auto k = static_cast<int>((trail.bits >> level) & 1u);
        probability *= k == 1 ? 1.0f - p0 : p0;
        pair = pairs_[pair].child[k];
    }
    return probability;
}

size_t LightTree::memory_bytes() const {
    return pairs_.capacity() * sizeof(ImportancePair) + trails_.capacity() * sizeof(Trail);
}

}  // namespace stratum
