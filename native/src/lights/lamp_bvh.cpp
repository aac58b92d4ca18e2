#include "lights/lamp_bvh.h"

#include <algorithm>
#include <cmath>

namespace stratum {

namespace {

float largest_magnitude(Vec3 v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

}  // namespace

LampBvh::LampBvh(const std::vector<Box>& boxes) {
    if (boxes.empty()) return;
    std::vector<Item> items;
    items.reserve(boxes.size());
    for (size_t i = 0; i < boxes.size(); ++i) {
        Box box = boxes[i];
        const Vec3 side = box.hi - box.lo;
        const float pad = kPadding * (std::max({side.x, side.y, side.z}) +
                                      std::max(largest_magnitude(box.lo), largest_magnitude(box.hi)));
        box.lo = box.lo - Vec3(pad, pad, pad);
        box.hi = box.hi + Vec3(pad, pad, pad);
        items.push_back({box, (box.lo + box.hi) * 0.5f, static_cast<uint32_t>(i)});
    }
    nodes_.reserve(2 * (items.size() / kLeafSize + 1));
    items_.reserve(items.size());
    build(items, 0, items.size());
}

void LampBvh::build(std::vector<Item>& items, size_t begin, size_t end) {
    const auto index = static_cast<uint32_t>(nodes_.size());
    Node node{items[begin].box.lo, items[begin].box.hi, 0, 0, 0};
    Vec3 centre_lo = items[begin].centre, centre_hi = centre_lo;
    for (size_t i = begin + 1; i < end; ++i) {
        node.lo = component_min(node.lo, items[i].box.lo);
        node.hi = component_max(node.hi, items[i].box.hi);
        centre_lo = component_min(centre_lo, items[i].centre);
        centre_hi = component_max(centre_hi, items[i].centre);
    }
    nodes_.push_back(node);
    if (end - begin <= kLeafSize) {
        nodes_[index].first = static_cast<uint32_t>(items_.size());
        nodes_[index].count = static_cast<uint32_t>(end - begin);
        for (size_t i = begin; i < end; ++i) items_.push_back(items[i].index);
        return;
    }
    const Vec3 extent = centre_hi - centre_lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    const auto first = items.begin() + static_cast<std::ptrdiff_t>(begin);
    const auto middle = first + static_cast<std::ptrdiff_t>((end - begin) / 2);
    std::nth_element(first, middle, items.begin() + static_cast<std::ptrdiff_t>(end),
                     [axis](const Item& a, const Item& b) {
                         return a.centre[axis] < b.centre[axis] ||
                                (a.centre[axis] == b.centre[axis] && a.index < b.index);
                     });
    const size_t split = begin + (end - begin) / 2;
    build(items, begin, split);
    nodes_[index].first = static_cast<uint32_t>(nodes_.size());
    nodes_[index].axis = axis;
    build(items, split, end);
}

}  // namespace stratum
