// The guiding tree as a render pass reads and feeds it (guiding/guiding_tree.h): the
// coordinates, the descents to a region and to a directional leaf, sampling p′ and its pdf,
// and the records. What happens between passes (folding the records, splitting, p′ anew) is in
// guiding/guiding_tree_learning.cpp.
#include "guiding/guiding_tree.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace stratum {

namespace {

constexpr double kTwoPi = 6.283185307179586;

// The largest double below 1: a rescaled coordinate stays in [0, 1).
constexpr double kBelowOne = 0x1.fffffffffffffp-1;

double clamp_unit(double v) { return std::clamp(v, 0.0, kBelowOne); }

// Probability of the lower child from the children's integrals; a node whose children both
// integrate to 0 (a region without light, copied from a parent that had some) halves evenly.
double lower_probability(double lower, double upper) {
    const double total = lower + upper;
    return total > 0.0 ? lower / total : 0.5;
}

}  // namespace

GuidingTree::GuidingTree(Vec3 center, float half_side, GuidingSplit split)
    : lo_(center - Vec3(half_side, half_side, half_side)), side_(2.0f * half_side), split_(split) {
    spatial_.push_back(SpatialNode{});
    directional_.push_back(DirectionalNode{});
    reset_counters();
}

Vec2 GuidingTree::direction_to_st(Vec3 d) {
    const double s = std::clamp((static_cast<double>(d.z) + 1.0) * 0.5, 0.0, kBelowOne);
    double t = std::atan2(static_cast<double>(d.y), static_cast<double>(d.x)) / kTwoPi;
    if (t < 0.0) t += 1.0;
    return {static_cast<float>(s), static_cast<float>(clamp_unit(t))};
}

Vec3 GuidingTree::st_to_direction(double s, double t) {
    const double cos_theta = std::clamp(2.0 * s - 1.0, -1.0, 1.0);
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    const double phi = kTwoPi * t;
    return {static_cast<float>(sin_theta * std::cos(phi)), static_cast<float>(sin_theta * std::sin(phi)),
            static_cast<float>(cos_theta)};
}

uint32_t GuidingTree::descend_spatial(const double coords[3], Box* box) const {
    *box = Box{{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}};
    uint32_t node = 0;
    while (spatial_[node].child != 0) {
        const uint8_t a = spatial_[node].axis;
        const double mid = 0.5 * (box->lo[a] + box->hi[a]);
        if (coords[a] < mid) {
            box->hi[a] = mid;
            node = spatial_[node].child;
        } else {
            box->lo[a] = mid;
            node = spatial_[node].child + 1;
        }
    }
    return node;
}

template <typename GoLower>
GuidingTree::DirectionalLeaf GuidingTree::descend_directional(uint32_t root, GoLower&& go_lower) const {
    DirectionalLeaf leaf{root, {0.0, 1.0, 0.0, 1.0}, 1.0};
    while (directional_[leaf.node].child != 0) {
        const DirectionalNode& n = directional_[leaf.node];
        const uint8_t a = n.axis;
        const double p_lower =
            lower_probability(directional_[n.child].integral, directional_[n.child + 1].integral);
        const double mid = 0.5 * (leaf.cell[2 * a] + leaf.cell[2 * a + 1]);
        if (go_lower(a, p_lower, mid)) {
            leaf.probability *= p_lower;
            leaf.cell[2 * a + 1] = mid;
            leaf.node = n.child;
        } else {
            leaf.probability *= 1.0 - p_lower;
            leaf.cell[2 * a] = mid;
            leaf.node = n.child + 1;
        }
    }
    return leaf;
}

GuidingTree::DirectionalLeaf GuidingTree::locate_directional(uint32_t root, Vec2 st) const {
    const double v[2] = {st.x, st.y};
    return descend_directional(root, [&](uint8_t axis, double, double mid) { return v[axis] < mid; });
}

double GuidingTree::DirectionalLeaf::solid_angle_pdf() const {
    const double area = (cell[1] - cell[0]) * (cell[3] - cell[2]);
    return probability / area * kInv4Pi;
}

uint32_t GuidingTree::region(Vec3 p) const {
    double coords[3];
    for (int a = 0; a < 3; ++a) coords[a] = clamp_unit((static_cast<double>(p[a]) - lo_[a]) / side_);
    Box box;
    return descend_spatial(coords, &box);
}

Vec3 GuidingTree::sample(uint32_t region, Vec2 u, float* pdf) const {
    const uint32_t root = spatial_[region].directional_root;
    if (!(directional_[root].integral > 0.0)) {
        *pdf = kInv4Pi;
        return st_to_direction(clamp_unit(u.x), clamp_unit(u.y));
    }
    // Hierarchical warping: each choice rescales the coordinate of its axis back to [0, 1).
    double uv[2] = {clamp_unit(u.x), clamp_unit(u.y)};
    const DirectionalLeaf leaf = descend_directional(root, [&](uint8_t axis, double p_lower, double) {
        if (uv[axis] < p_lower) {
            uv[axis] = clamp_unit(uv[axis] / p_lower);
            return true;
        }
        uv[axis] = clamp_unit((uv[axis] - p_lower) / (1.0 - p_lower));
        return false;
    });
    *pdf = static_cast<float>(leaf.solid_angle_pdf());
    const double* cell = leaf.cell;
    return st_to_direction(cell[0] + uv[0] * (cell[1] - cell[0]), cell[2] + uv[1] * (cell[3] - cell[2]));
}

float GuidingTree::pdf(uint32_t region, Vec3 direction) const {
    const uint32_t root = spatial_[region].directional_root;
    if (!(directional_[root].integral > 0.0)) return kInv4Pi;
    return static_cast<float>(locate_directional(root, direction_to_st(direction)).solid_angle_pdf());
}

std::atomic<uint64_t>* GuidingTree::counters_of_spatial(uint32_t node) const {
    return counters_.get() + spatial_[node].counters;
}

std::atomic<uint64_t>* GuidingTree::counters_of_directional(uint32_t node) const {
    return counters_.get() + directional_[node].counters;
}

void GuidingTree::record(Vec3 position, Vec3 direction, float luminance) {
    if (!counters_ || !std::isfinite(luminance) || luminance < 0.0f || !is_finite(position) ||
        !is_finite(direction))
        return;
    const auto units = static_cast<uint64_t>(
        std::llround(static_cast<double>(std::min(luminance, kMaxRecordLuminance)) * kUnitsPerLuminance));
    double coords[3];
    for (int a = 0; a < 3; ++a) coords[a] = clamp_unit((static_cast<double>(position[a]) - lo_[a]) / side_);
    Box box;
    const uint32_t leaf = descend_spatial(coords, &box);
    uint32_t cell_bin = 0;
    for (int a = 0; a < 3; ++a)
        cell_bin = cell_bin * kSpatialHistogramSide +
                   std::min(kSpatialHistogramSide - 1,
                            static_cast<uint32_t>((coords[a] - box.lo[a]) / (box.hi[a] - box.lo[a]) *
                                                  kSpatialHistogramSide));
    std::atomic<uint64_t>* c = counters_of_spatial(leaf) + 2 * cell_bin;
    c[0].fetch_add(1, std::memory_order_relaxed);
    c[1].fetch_add(units, std::memory_order_relaxed);
    const Vec2 st = direction_to_st(direction);
    const DirectionalLeaf cell = locate_directional(spatial_[leaf].directional_root, st);
    const auto bin = [](double v, double lo, double hi) {
        return std::min(kHistogramSide - 1, static_cast<uint32_t>((v - lo) / (hi - lo) * kHistogramSide));
    };
    const uint32_t b =
        bin(st.x, cell.cell[0], cell.cell[1]) * kHistogramSide + bin(st.y, cell.cell[2], cell.cell[3]);
    c = counters_of_directional(cell.node) + 2 * b;
    c[0].fetch_add(1, std::memory_order_relaxed);
    c[1].fetch_add(units, std::memory_order_relaxed);
}

size_t GuidingTree::region_count() const {
    return static_cast<size_t>(
        std::count_if(spatial_.begin(), spatial_.end(), [](const SpatialNode& n) { return n.child == 0; }));
}

size_t GuidingTree::bytes() const {
    return spatial_.size() * sizeof(SpatialNode) + directional_.size() * sizeof(DirectionalNode) +
           counter_count_ * sizeof(std::atomic<uint64_t>);
}

}  // namespace stratum
