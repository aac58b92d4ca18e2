#include "lights/light_tree.h"

#include <algorithm>
#include <array>
#include <limits>

namespace stratum {

LightTree::LightTree(const std::vector<LightBounds>& bounds, const std::vector<uint32_t>& light) {
    std::vector<Item> items;
    uint32_t lights = 0;
    for (size_t i = 0; i < bounds.size(); ++i) {
        lights = std::max(lights, light[i] + 1);
        if (bounds[i].phi > 0.0) items.push_back({bounds[i], light[i]});
    }
    trails_.resize(lights);
    if (items.empty()) return;
    nodes_.reserve(2 * items.size() - 1);
    build(items, 0, items.size(), 0, 0);
}

LightBounds LightTree::build(std::vector<Item>& items, size_t begin, size_t end, uint64_t bits,
                             uint32_t depth) {
    depth_ = std::max(depth_, depth);
    const auto index = static_cast<uint32_t>(nodes_.size());
    nodes_.push_back({ImportanceBound(items[begin].bounds), 0, true});
    if (end - begin == 1) {
        const Item& item = items[begin];
        nodes_[index] = {ImportanceBound(item.bounds), item.light, true};
        trails_[item.light] = {bits, depth, index};
        return item.bounds;
    }
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
    build(items, begin, split, bits, depth + 1);
    const auto second = static_cast<uint32_t>(nodes_.size());
    build(items, split, end, bits | (uint64_t{1} << depth), depth + 1);
    nodes_[index] = {ImportanceBound(all), second, false};
    return all;
}

float LightTree::first_child_probability(uint32_t node, Vec3 p, Vec3 n) const {
    const double i0 = importance(nodes_[node + 1].bound, p, n);
    const double i1 = importance(nodes_[nodes_[node].child_or_light].bound, p, n);
    if (!(i0 + i1 > 0.0)) return -1.0f;
    return static_cast<float>(i0 / (i0 + i1));
}

uint32_t LightTree::choose(Vec3 p, Vec3 n, float u, float* pmf) const {
    *pmf = 0.0f;
    if (nodes_.empty()) return kNone;
    // The root alone: a tree of one light takes it wherever it can contribute.
    if (nodes_[0].leaf) {
        if (!(importance(nodes_[0].bound, p, n) > 0.0)) return kNone;
        *pmf = 1.0f;
        return nodes_[0].child_or_light;
    }
    float probability = 1.0f;
    uint32_t node = 0;
    while (!nodes_[node].leaf) {
        const float p0 = first_child_probability(node, p, n);
        if (p0 < 0.0f) return kNone;
        if (u < p0) {
            u = std::min(u / p0, kOneMinusEpsilon);
            probability *= p0;
            node = node + 1;
        } else {
            u = std::min((u - p0) / (1.0f - p0), kOneMinusEpsilon);
            probability *= 1.0f - p0;
            node = nodes_[node].child_or_light;
        }
    }
    *pmf = probability;
    return nodes_[node].child_or_light;
}

float LightTree::pmf(Vec3 p, Vec3 n, uint32_t light) const {
    if (light >= trails_.size() || trails_[light].leaf == kNone) return 0.0f;
    if (nodes_[0].leaf) return importance(nodes_[0].bound, p, n) > 0.0 ? 1.0f : 0.0f;
    const Trail& trail = trails_[light];
    float probability = 1.0f;
    uint32_t node = 0;
    for (uint32_t level = 0; level < trail.depth; ++level) {
        const float p0 = first_child_probability(node, p, n);
        if (p0 < 0.0f) return 0.0f;
        if ((trail.bits >> level) & 1u) {
            probability *= 1.0f - p0;
            node = nodes_[node].child_or_light;
        } else {
            probability *= p0;
            node = node + 1;
        }
    }
    return probability;
}

size_t LightTree::memory_bytes() const {
    return nodes_.capacity() * sizeof(Node) + trails_.capacity() * sizeof(Trail);
}

}  // namespace stratum
