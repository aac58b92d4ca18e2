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

    bool empty() const { return nodes_.empty(); }
    // The caller's light for u in [0, 1) at (p, n) and its probability (*pmf); kNone (pmf 0)
    // when the tree is empty or no light can reach p.
    uint32_t choose(Vec3 p, Vec3 n, float u, float* pmf) const;
    // The probability choose() takes the caller's light `light` with at (p, n); 0 for a light
    // not in the tree.
    float pmf(Vec3 p, Vec3 n, uint32_t light) const;
    // Bytes held by the tree (nodes and per-light trails), for the build report.
    size_t memory_bytes() const;
    uint32_t depth() const { return depth_; }
    size_t node_count() const { return nodes_.size(); }

private:
    struct Node {
        ImportanceBound bound;
        // Inner node: the second child's index (the first is the next node); leaf: the light.
        uint32_t child_or_light;
        bool leaf;
    };
    struct Trail {
        uint64_t bits = 0;  // bit k: the branch taken at depth k (1 = second child)
        uint32_t depth = 0;
        uint32_t leaf = kNone;
    };
    struct Item {
        LightBounds bounds;
        uint32_t light;
    };
    LightBounds build(std::vector<Item>& items, size_t begin, size_t end, uint64_t bits, uint32_t depth);
    // Probability of the first child of inner node `node` at (p, n); negative when both are 0.
    float first_child_probability(uint32_t node, Vec3 p, Vec3 n) const;

    std::vector<Node> nodes_;
    std::vector<Trail> trails_;  // by the caller's light index
    uint32_t depth_ = 0;
};

}  // namespace stratum
