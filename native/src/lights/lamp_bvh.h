// A bounding volume hierarchy over the lamps that rays meet outside the scene's BVH (area lamps,
// point and spot lamps with a radius: LightSet::lamp_radiance), so that a ray tests the few
// lamps whose boxes it crosses instead of every lamp: every camera and BSDF ray asks, and with
// 1,000 lamps a loop over all of them cost more than the ray's trace through the scene.
//
// | parameter  | meaning                                                                        |
// |------------|--------------------------------------------------------------------------------|
// | kLeafSize  | lamps per leaf at most (a leaf's lamps are tested in a row)                     |
// | kPadding   | each box grows by kPadding × (its largest side + its largest coordinate's     |
// |            | magnitude): float rounding of the slab test or of a lamp's hit point never     |
// |            | prunes a lamp that intersect() would meet (the pruning must be conservative)   |
//
// Build: top down, median split by count along the widest axis of the boxes' centres (ties by
// item number, so the build is deterministic). Traversal: the slab test (Kay & Kajiya 1986) of
// each node's box against [0, t_limit], t_limit read again at every node so that the caller's
// nearest hit prunes what lies behind it; the nearer child first.
#pragma once

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/math.h"
#include "lights/light_bounds.h"

namespace stratum {

class LampBvh {
public:
    static constexpr uint32_t kLeafSize = 4;
    static constexpr float kPadding = 1e-5f;

    struct Box {
        Vec3 lo, hi;
    };

    LampBvh() = default;
    // A hierarchy over boxes[i], i the item number visit() reports.
    explicit LampBvh(const std::vector<Box>& boxes);

    bool empty() const { return nodes_.empty(); }

    // Calls visit(item) for every item whose (padded) box the ray origin + t dir meets at some
    // t in [0, t_limit]; visit may lower t_limit (the nearest hit so far) as it goes.
    template <typename Visit>
    void visit(Vec3 origin, Vec3 dir, const float& t_limit, Visit&& visit) const {
        if (nodes_.empty()) return;
        const Vec3 inv(1.0f / dir.x, 1.0f / dir.y, 1.0f / dir.z);
        uint32_t stack[64];
        uint32_t top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const Node& node = nodes_[stack[--top]];
            if (!meets(node, origin, dir, inv, t_limit)) continue;
            if (node.count > 0) {
                for (uint32_t k = node.first; k < node.first + node.count; ++k) visit(items_[k]);
                continue;
            }
            // Inner node: first child next, second at node.first. The nearer goes on top.
            const uint32_t self = static_cast<uint32_t>(&node - nodes_.data());
            const bool second_nearer = dir[node.axis] < 0.0f;
            stack[top++] = second_nearer ? self + 1 : node.first;
            stack[top++] = second_nearer ? node.first : self + 1;
        }
    }

private:
    struct Node {
        Vec3 lo, hi;
        uint32_t first;  // leaf: first of its items; inner: the second child's node
        uint32_t count;  // leaf: its items (> 0); inner: 0
        int axis;        // inner: the axis split along
    };
    struct Item {
        Box box;
        Vec3 centre;
        uint32_t index;
    };
    void build(std::vector<Item>& items, size_t begin, size_t end);
    // The slab test: the ray meets the node's box at some t in [0, t_limit] (widened by kPadding
    // relative, the pruning stays conservative).
    static bool meets(const Node& node, Vec3 origin, Vec3 dir, Vec3 inv, float t_limit) {
        float t0 = 0.0f, t1 = t_limit * (1.0f + 4.0f * kPadding);
        for (int axis = 0; axis < 3; ++axis) {
            const float o = origin[axis];
            if (dir[axis] == 0.0f) {
                // Parallel to the slab: inside it or never (1/0 would give 0 × ∞ = NaN).
                if (o < node.lo[axis] || o > node.hi[axis]) return false;
                continue;
            }
            float near = (node.lo[axis] - o) * inv[axis], far = (node.hi[axis] - o) * inv[axis];
            if (near > far) std::swap(near, far);
            t0 = std::max(t0, near);
            t1 = std::min(t1, far);
            if (t0 > t1) return false;
        }
        return true;
    }

    std::vector<Node> nodes_;
    std::vector<uint32_t> items_;  // item numbers in leaf order
};

}  // namespace stratum
