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
// three axes of the centroid box, with the least summed cost Φ M_Ω area K_r N of the two sides
// (N the side's light count, as a ray BVH's SAH weighs it; the paper's cost has no N, which
// built 1,000 random lamps 28 levels deep instead of 12); leaves hold one light. Lights of zero
// power emit nothing and are left out (pmf 0).
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
// Adaptive splitting (Conty Estévez & Kulla 2018 §5): cut() descends from the root and, while
// the cut holds fewer than max_cut nodes, replaces one inner node by its two children: of the
// nodes whose sin θ_b = r/d (the bounding sphere's radius over the distance from p to its
// centre, that distance taken as at least r/100) exceeds kSplitThreshold, the one of largest
// I (r/d)², I its importance at (p, n). r/d measures how loose the node's importance bound is
// at p: every angle bound of light_bounds.h is widened by θ_b and d² is clamped to r², so a
// node seen under a small angle weighs what its lights give to within their orientation
// spread, one seen under a wide angle may hold lights far nearer and farther than its centre
// (the paper's heuristic, the variance of the contribution over the bounding sphere, grows with
// r/d too and costs an integral per node); the factor I spends the splits where the light is
// (on the many-lights hall it gave 5% less MSE than r/d alone at 8 nodes). Each cut node is a
// separate sub-estimator choosing one light below it as choose() does; a light's probability is
// the product of the branch probabilities below its cut node (1 when the node is the light).
// The cut depends on (p, n) alone and is computed with the same float operations by cut() for
// choose_in_cut() and by pmf(..., max_cut), so the pmf a BSDF ray's MIS weight uses is that of
// the light sample bit for bit. max_cut = 1 is the unsplit tree (bit-identical images).
// Measured with `stratum compare` (sobol, 4–64 spp, MSE at equal path-tracing time, against
// the unsplit tree): many-lights hall (96 × 54) 4 nodes 0.83×, 8 nodes 0.41×, 16 nodes 0.44×
// (per sample 0.40×, 0.13×, 0.077×; 8 nodes against power selection 0.15×); features/lights
// 0.49× at 8; the Cornell box with tree chosen 0.81×; its large-light variant 1.11×, the one
// loss: a two-triangle lamp seen under a wide angle from everywhere is split everywhere, and
// the second shadow ray costs 40% for 20% less MSE. Inside a closed emissive sphere (every
// vertex sees every node wide) a sample takes 3.3x the time, for no gain: NEE there is already
// exact. Hence light_tree_splits defaults to 8; auto takes the tree only for more than three
// lights, so the large-light box keeps one light sample, but a large emissive mesh does not (not
// splitting within one emitting mesh would spare it; not built).
// Importance: pbrt-v4's single bound. Cycles 5.0 averages the bound from above (as here) with a
// bound from below (the least contribution over the cluster), which helps where many clusters
// share a maximum; the upper bound alone is the paper's measure, it is 0 only where nothing can
// contribute (the property unbiasedness needs) and costs one evaluation per child.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "lights/light_bounds.h"

namespace stratum {

class LightTree {
public:
    static constexpr int kBuckets = 12;
    static constexpr uint32_t kMedianDepth = 32;
    static constexpr uint32_t kNone = 0xffffffffu;
    // Most nodes a cut may hold (the setting light_tree_splits' maximum), and the r/d above
    // which a node is split (header; measured on the many-lights hall, docs/study.md).
    static constexpr uint32_t kMaxCut = 16;
    static constexpr float kSplitThreshold = 0.5f;

    // One node of a cut: an inner node (pair) or a leaf (light), where it sits in the tree (the
    // root→node branch bits, as in Trail) and its bounding sphere, for the split test.
    struct CutNode {
        uint32_t pair = kNone;    // the node's pair when inner, else kNone
        uint32_t light = kNone;   // the caller's light when a leaf
        uint32_t parent = kNone;  // a leaf's bound: lane `lane` of this pair (kNone: single_)
        uint32_t lane = 0;
        uint32_t depth = 0;
        uint64_t bits = 0;
        float split_score = 0.0f;  // (r/d)², d ≥ r/100; < 0: never split (a leaf)
        float priority = 0.0f;     // of the nodes loose enough to split, the highest goes first
    };
    // The cut at a shading point: a fixed-size array, nothing allocated per sample.
    struct Cut {
        std::array<CutNode, kMaxCut> node{};
        uint32_t size = 0;
    };

    // A tree over bounds[i] for every i with phi > 0; `light` numbers them in the caller's list.
    LightTree(const std::vector<LightBounds>& bounds, const std::vector<uint32_t>& light);

    bool empty() const { return pairs_.empty() && !has_single_; }
    // The caller's light for u in [0, 1) at (p, n) and its probability (*pmf); kNone (pmf 0)
    // when the tree is empty or no light can reach p.
    uint32_t choose(Vec3 p, Vec3 n, float u, float* pmf) const;
    // The probability choose() takes the caller's light `light` with at (p, n); 0 for a light
    // not in the tree.
    float pmf(Vec3 p, Vec3 n, uint32_t light) const;
    // The cut at (p, n) of at most max_cut (1..kMaxCut) nodes (header); one node, the root, when
    // max_cut is 1 or the tree holds a single light; empty when the tree is empty.
    void cut(Vec3 p, Vec3 n, uint32_t max_cut, Cut* out) const;
    // The caller's light the sub-estimator of `node` takes for u in [0, 1) at (p, n), and its
    // probability below the node (*pmf); kNone (pmf 0) when no light below it can reach p.
    uint32_t choose_in_cut(const CutNode& node, Vec3 p, Vec3 n, float u, float* pmf) const;
    // The probability with which the sub-estimator of light's cut node takes `light` at (p, n)
    // under a cut of at most max_cut nodes; pmf(p, n, light) when max_cut is 1.
    float pmf(Vec3 p, Vec3 n, uint32_t light, uint32_t max_cut) const;
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
    // choose()'s descent from pair `pair` for u, `probability` the product of the branch
    // probabilities above it.
    uint32_t descend(uint32_t pair, Vec3 p, Vec3 n, bool has_normal, float u, float probability,
                     float* pmf) const;
    // The split score of a node of bounding sphere (centre, radius) at p (CutNode::split_score).
    static float split_score(float cx, float cy, float cz, float radius, Vec3 p);
    // Node k of pair `pair` as a cut node below a parent of branch bits `bits` at depth `depth`.
    CutNode child_node(uint32_t pair, int k, uint64_t bits, uint32_t depth, Vec3 p, Vec3 n,
                       bool has_normal) const;
    // 1 where the leaf cut node's light can contribute at (p, n), else 0.
    float pmf_of_leaf(const CutNode& leaf, Vec3 p, Vec3 n) const;
    // Probability of the first child of pair `pair` at (p, n); negative when both weigh 0.
    float first_child_probability(uint32_t pair, Vec3 p, Vec3 n, bool has_normal) const;

    // Inner nodes, the root first; each holds both children's bounds (lights/light_bounds.h).
    std::vector<ImportancePair> pairs_;
    // A tree of one light has no inner node: that light and its bound (lane 0).
    ImportancePair single_{};
    bool has_single_ = false;
    std::vector<Trail> trails_;  // by the caller's light index
    // The root's bounding sphere (its bound lives in no pair), for the split test.
    float root_centre_[3] = {0.0f, 0.0f, 0.0f};
    float root_radius_ = 0.0f;
    uint32_t depth_ = 0;
};

}  // namespace stratum
