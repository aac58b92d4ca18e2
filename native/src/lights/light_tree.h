// The light tree: a binary BVH over the bounds of the finite lights (point, spot and area lamps,
// emissive triangles) that picks one light for a shading point by descending from the root,
// taking each child with probability proportional to its importance there.
//
// | parameter      | meaning                                                                  |
// |----------------|--------------------------------------------------------------------------|
// | kBuckets       | 12 bins along each axis for the split search (pbrt-v4's count)            |
// | kMedianDepth   | from this depth on, splits are at the median by count, so that a trail of |
// |                | root→leaf branch bits fits 64 bits for up to 2^32 lights                  |
// | importance     | lights/light_bounds.h (Conty Estévez & Kulla 2018 §4.3)                   |
//
// Build (Conty Estévez & Kulla 2018, §4.2; pbrt-v4 BVHLightSampler::buildBVH): top down, each
// node's lights split into two by the plane, among kBuckets bucket boundaries on each of the
// three axes of the centroid box, with the least summed cost Φ M_Ω area K_r of the two sides;
// leaves hold one light. Lights of zero power emit nothing and are left out (pmf 0).
//
// Choice (one light per shading point, no splitting; pbrt-v4 BVHLightSampler::Sample): at each
// inner node the children's importances I_0, I_1 at (p, n) give p_0 = I_0/(I_0 + I_1); u < p_0
// goes left with u/p_0, else right with (u − p_0)/(1 − p_0). The pmf is the product of the
// branch probabilities; pmf() recomputes it from the light's bit trail with the same operations,
// so it equals the probability choose() returns bit for bit. Both zero: no light can reach p.
// Layout: one ImportancePair per inner node holds the bounds of both its children side by side
// (and their indices), so a descent step reads one 128-byte block and evaluates both children
// in float (light_bounds.h); leaves live in their parent's pair. Φ is stored over the tree's
// total: probabilities are ratios, and the scale keeps float importances finite.
// Importance: pbrt-v4's single bound. Cycles 5.0 averages the bound from above (as here) with a
// bound from below (the least contribution over the cluster), which helps where many clusters
// share a maximum; the upper bound alone is the paper's measure, it is 0 only where nothing can
// contribute (the property unbiasedness needs) and costs one evaluation per child.
#pragma once

#include <cstdint>
#include <vector>

#include "lights/light_bounds.h"

namespace stratum {

class LightTree {
public:
    static constexpr int kBuckets = 12;
    static constexpr uint32_t kMedianDepth = 32;
    static constexpr uint32_t kNone = 0xffffffffu;

    // A tree over bounds[i] for every i with phi > 0; `light` numbers them in the caller's list.
    LightTree(const std::vector<LightBounds>& bounds, const std::vector<uint32_t>& light);

    bool empty() const { return pairs_.empty() && !has_single_; }
    // The caller's light for u in [0, 1) at (p, n) and its probability (*pmf); kNone (pmf 0)
    // when the tree is empty or no light can reach p.
    uint32_t choose(Vec3 p, Vec3 n, float u, float* pmf) const;
    // The probability choose() takes the caller's light `light` with at (p, n); 0 for a light
    // not in the tree.
    float pmf(Vec3 p, Vec3 n, uint32_t light) const;
    // Bytes held by the tree (nodes and per-light trails), for the build report.
    size_t memory_bytes() const;
    uint32_t depth() const { return depth_; }
    // Inner nodes and leaves.
    size_t node_count() const { return has_single_ ? 1 : (pairs_.empty() ? 0 : 2 * pairs_.size() + 1); }

private:
    struct Trail {
        uint64_t bits = 0;  // bit k: the branch taken at depth k (1 = second child)
        uint32_t depth = 0;
        bool in_tree = false;
    };
    struct Item {
        LightBounds bounds;
        uint32_t light;
    };
    // Builds items [begin, end) (two or more) into pairs_[index] and below; returns their bound.
    LightBounds build(std::vector<Item>& items, size_t begin, size_t end, uint64_t bits, uint32_t depth,
                      double phi_scale);
    // Probability of the first child of pair `pair` at (p, n); negative when both weigh 0.
    float first_child_probability(uint32_t pair, Vec3 p, Vec3 n, bool has_normal) const;

    // Inner nodes, the root first; each holds both children's bounds (lights/light_bounds.h).
    std::vector<ImportancePair> pairs_;
    // A tree of one light has no inner node: that light and its bound (lane 0).
    ImportancePair single_{};
    bool has_single_ = false;
    std::vector<Trail> trails_;  // by the caller's light index
    uint32_t depth_ = 0;
};

}  // namespace stratum
