// How the guiding tree learns (guiding/guiding_tree.h), between passes in one thread:
// update() folds the pass's per-leaf counters into the totals, splits the leaves past their
// thresholds (directional first, then spatial, by GuidingSplit) and recomputes p′ from the
// floored means; stop_learning() ends it. The render pass's side (records, sampling) is in
// guiding/guiding_tree.cpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "guiding/guiding_tree.h"

namespace stratum {

namespace {

// A leaf that took more records in one pass drops the pass: its 64-bit luminance sum may have
// wrapped (header).
constexpr uint64_t kMaxPassRecords = uint64_t{1} << 31;
// A leaf splits only on a pass that brought it this many records: the halves' counts then say
// something about where within the cell the records (and their radiance) lie.
constexpr uint64_t kMinPassRecordsToSplit = 16;

}  // namespace

std::span<const RegistryEntry> guiding_split_choices() {
    static constexpr std::array kSplits = {
        RegistryEntry{"binary", "Binary",
                      "A node splits in two along the axis its records tell apart most (textbook §5)"},
        RegistryEntry{"full", "All Axes",
                      "A node splits along every axis at once: 8 octants of space, 4 quadrants of "
                      "directions, the book's 32 children (textbook §5)"},
    };
    return kSplits;
}

void GuidingTree::fold_directional(uint32_t node, double st_box[4], std::vector<uint32_t>* to_split,
                                   std::vector<std::array<double, 2>>* sides) {
    DirectionalNode& n = directional_[node];
    if (n.child != 0) {
        const uint8_t a = n.axis;
        const double mid = 0.5 * (st_box[2 * a] + st_box[2 * a + 1]);
        double lower[4] = {st_box[0], st_box[1], st_box[2], st_box[3]};
        double upper[4] = {st_box[0], st_box[1], st_box[2], st_box[3]};
        lower[2 * a + 1] = mid;
        upper[2 * a] = mid;
        const uint32_t child = n.child;
        fold_directional(child, lower, to_split, sides);
        fold_directional(child + 1, upper, to_split, sides);
        return;
    }
    const std::atomic<uint64_t>* c = counters_of_directional(node);
    uint64_t count = 0, units = 0;
    for (size_t k = 0; k < kDirectionalCounters; k += 2) {
        count += c[k].load(std::memory_order_relaxed);
        units += c[k + 1].load(std::memory_order_relaxed);
    }
    if (count == 0 || count > kMaxPassRecords) return;
    n.totals.count += static_cast<double>(count);
    n.totals.sum += static_cast<double>(units) / kUnitsPerLuminance;
    to_split->push_back(node);
    sides->push_back({st_box[1] - st_box[0], st_box[3] - st_box[2]});
}

GuidingTree::BinCounts GuidingTree::bin_counts(const Histogram& h, const BinRange& r) {
    BinCounts c;
    const uint32_t mid_i = (r.i0 + r.i1) / 2, mid_j = (r.j0 + r.j1) / 2;
    for (uint32_t i = r.i0; i < r.i1; ++i)
        for (uint32_t j = r.j0; j < r.j1; ++j) {
            const uint32_t b = i * kHistogramSide + j;
            c.count += h.count[b];
            c.sum += h.sum[b];
            if (i < mid_i) c.lower_count[0] += h.count[b], c.lower_sum[0] += h.sum[b];
            if (j < mid_j) c.lower_count[1] += h.count[b], c.lower_sum[1] += h.sum[b];
        }
    return c;
}

uint32_t GuidingTree::halve_directional(uint32_t node, uint8_t axis, const BinCounts& c) {
    const double count_share = c.count > 0.0 ? c.lower_count[axis] / c.count : 0.5;
    const double sum_share = c.sum > 0.0 ? c.lower_sum[axis] / c.sum : count_share;
    const DirectionalNode parent = directional_[node];
    const auto child = static_cast<uint32_t>(directional_.size());
    DirectionalNode lower, upper;
    lower.depth = upper.depth = static_cast<uint8_t>(parent.depth + 1);
    lower.totals = {parent.totals.count * count_share, parent.totals.sum * sum_share};
    upper.totals = {parent.totals.count * (1.0 - count_share), parent.totals.sum * (1.0 - sum_share)};
    directional_.push_back(lower);
    directional_.push_back(upper);
    directional_[node].child = child;
    directional_[node].axis = axis;
    return child;
}

void GuidingTree::refine_directional(uint32_t node, const Histogram& h, const BinRange& r, double cell_s,
                                     double cell_t) {
    const DirectionalNode& n = directional_[node];
    if (n.totals.count < kDirectionalThreshold || n.depth >= kMaxDirectionalDepth ||
        node_count() + 6 > kMaxNodes)
        return;
    const BinCounts c = bin_counts(h, r);
    const bool splittable[2] = {r.i1 - r.i0 > 1, r.j1 - r.j0 > 1};
    if (c.count < kMinPassRecordsToSplit || (!splittable[0] && !splittable[1])) return;
    uint8_t axis = splittable[0] ? 0 : 1;
    if (split_ == GuidingSplit::Binary) {
        // The axis whose halves' mean radiance differs most; an empty half counts as dark (its
        // directions drew no records: below the surfaces, or where the guide sent no samples).
        // Equal differences: the longer side of the cell.
        double difference[2] = {-1.0, -1.0};
        for (int a = 0; a < 2; ++a) {
            if (!splittable[a]) continue;
            const double upper_count = c.count - c.lower_count[a];
            const double lower_mean = c.lower_count[a] > 0.0 ? c.lower_sum[a] / c.lower_count[a] : 0.0;
            const double upper_mean = upper_count > 0.0 ? (c.sum - c.lower_sum[a]) / upper_count : 0.0;
            difference[a] = std::abs(lower_mean - upper_mean);
        }
        axis = difference[1] > difference[0] ? 1 : 0;
        if (difference[0] == difference[1]) axis = cell_t > cell_s ? 1 : 0;
    }
    const uint32_t child = halve_directional(node, axis, c);
    const uint32_t mid_i = (r.i0 + r.i1) / 2, mid_j = (r.j0 + r.j1) / 2;
    const BinRange halves[2] = {
        axis == 0 ? BinRange{r.i0, mid_i, r.j0, r.j1} : BinRange{r.i0, r.i1, r.j0, mid_j},
        axis == 0 ? BinRange{mid_i, r.i1, r.j0, r.j1} : BinRange{r.i0, r.i1, mid_j, r.j1}};
    const double half_s = axis == 0 ? 0.5 * cell_s : cell_s, half_t = axis == 1 ? 0.5 * cell_t : cell_t;
    if (split_ == GuidingSplit::Full && axis == 0 && splittable[1]) {
        // The book's split along every axis: both halves split along t as well (4 quadrants),
        // then each quadrant refines on its own.
        for (uint32_t k = 0; k < 2; ++k) {
            const uint32_t quadrants = halve_directional(child + k, 1, bin_counts(h, halves[k]));
            const BinRange& q = halves[k];
            refine_directional(quadrants, h, {q.i0, q.i1, q.j0, mid_j}, half_s, 0.5 * cell_t);
            refine_directional(quadrants + 1, h, {q.i0, q.i1, mid_j, q.j1}, half_s, 0.5 * cell_t);
        }
        return;
    }
    refine_directional(child, h, halves[0], half_s, half_t);
    refine_directional(child + 1, h, halves[1], half_s, half_t);
}

void GuidingTree::copy_directional(uint32_t from, uint32_t to, double share) {
    DirectionalNode n = directional_[from];
    n.totals.count *= share;
    n.totals.sum *= share;
    const uint32_t from_child = n.child;
    if (from_child != 0) {
        // Children stay adjacent: their pair is appended before either subtree.
        n.child = static_cast<uint32_t>(directional_.size());
        directional_.resize(directional_.size() + 2);
    }
    directional_[to] = n;
    if (from_child != 0) {
        copy_directional(from_child, n.child, share);
        copy_directional(from_child + 1, n.child + 1, share);
    }
}

void GuidingTree::scale_directional(uint32_t node, double share) {
    directional_[node].totals.count *= share;
    directional_[node].totals.sum *= share;
    if (const uint32_t child = directional_[node].child; child != 0) {
        scale_directional(child, share);
        scale_directional(child + 1, share);
    }
}

GuidingTree::SpatialCounts GuidingTree::spatial_counts(const SpatialHistogram& h, const SpatialRange& r) {
    SpatialCounts c;
    uint32_t mid[3];
    for (int a = 0; a < 3; ++a) mid[a] = (r.lo[a] + r.hi[a]) / 2;
    for (uint32_t x = r.lo[0]; x < r.hi[0]; ++x)
        for (uint32_t y = r.lo[1]; y < r.hi[1]; ++y)
            for (uint32_t z = r.lo[2]; z < r.hi[2]; ++z) {
                const uint32_t b = (x * kSpatialHistogramSide + y) * kSpatialHistogramSide + z;
                const uint32_t v[3] = {x, y, z};
                c.count += h.count[b];
                c.sum += h.sum[b];
                for (int a = 0; a < 3; ++a)
                    if (v[a] < mid[a]) c.lower_count[a] += h.count[b], c.lower_sum[a] += h.sum[b];
            }
    return c;
}

bool GuidingTree::halve_spatial(uint32_t node, int axis, const SpatialCounts& c) {
    // The upper half copies the region's directional tree: refused past kMaxNodes.
    size_t size = 0;
    for (std::vector<uint32_t> stack{spatial_[node].directional_root}; !stack.empty();) {
        const uint32_t d = stack.back();
        stack.pop_back();
        ++size;
        if (directional_[d].child != 0)
            stack.insert(stack.end(), {directional_[d].child, directional_[d].child + 1});
    }
    if (node_count() + 2 + size > kMaxNodes) return false;
    const double count_share = c.count > 0.0 ? c.lower_count[axis] / c.count : 0.5;
    const double sum_share = c.sum > 0.0 ? c.lower_sum[axis] / c.sum : count_share;
    const SpatialNode parent = spatial_[node];
    const auto child = static_cast<uint32_t>(spatial_.size());
    SpatialNode lower, upper;
    lower.depth = upper.depth = static_cast<uint8_t>(parent.depth + 1);
    lower.totals = {parent.totals.count * count_share, parent.totals.sum * sum_share};
    upper.totals = {parent.totals.count * (1.0 - count_share), parent.totals.sum * (1.0 - sum_share)};
    // Both halves start from the region's directional distribution, their counts scaled to the
    // share of the records they took, so each refines it from where the parent left off.
    upper.directional_root = static_cast<uint32_t>(directional_.size());
    directional_.emplace_back();
    copy_directional(parent.directional_root, upper.directional_root, 1.0 - count_share);
    lower.directional_root = parent.directional_root;
    scale_directional(lower.directional_root, count_share);
    spatial_.push_back(lower);
    spatial_.push_back(upper);
    spatial_[node].child = child;
    spatial_[node].axis = static_cast<uint8_t>(axis);
    return true;
}

void GuidingTree::refine_spatial(uint32_t node, const SpatialHistogram& h, const SpatialRange& r,
                                 const Box& box, int forced_axis) {
    if (forced_axis > 2) forced_axis = -1;
    const SpatialCounts c = spatial_counts(h, r);
    bool splittable[3];
    for (int a = 0; a < 3; ++a) splittable[a] = r.hi[a] - r.lo[a] > 1;
    int axis = -1;
    if (forced_axis >= 0) {
        // Inside the book's split into octants: the next axis, whatever the counts.
        axis = forced_axis;
    } else {
        const SpatialNode& n = spatial_[node];
        if (n.totals.count < kSpatialThreshold || n.depth >= kMaxSpatialDepth ||
            c.count < kMinPassRecordsToSplit)
            return;
        if (split_ == GuidingSplit::Full) {
            axis = 0;
        } else {
            // The axis along which the records spread most: extent × balance of the two halves
            // (a wall's records all lie in one half of its normal axis, which is not split).
            double best = 0.0;
            for (int a = 0; a < 3; ++a) {
                if (!splittable[a]) continue;
                const double balance =
                    4.0 * c.lower_count[a] * (c.count - c.lower_count[a]) / (c.count * c.count);
                const double score = (box.hi[a] - box.lo[a]) * balance;
                if (score > best) best = score, axis = a;
            }
        }
    }
    if (axis < 0 || !splittable[axis] || !halve_spatial(node, axis, c)) return;
    const uint32_t child = spatial_[node].child;
    SpatialRange lower_range = r, upper_range = r;
    lower_range.hi[axis] = upper_range.lo[axis] = (r.lo[axis] + r.hi[axis]) / 2;
    Box lower_box = box, upper_box = box;
    lower_box.hi[axis] = upper_box.lo[axis] = 0.5 * (box.lo[axis] + box.hi[axis]);
    const int next = split_ == GuidingSplit::Full && axis < 2 ? axis + 1 : -1;
    refine_spatial(child, h, lower_range, lower_box, next);
    refine_spatial(child + 1, h, upper_range, upper_box, next);
}

double GuidingTree::integrate(uint32_t node, double floor, double area) {
    DirectionalNode& n = directional_[node];
    if (n.child == 0) {
        n.mean = std::max(n.totals.count > 0.0 ? n.totals.sum / n.totals.count : 0.0, floor);
        n.integral = n.mean * area;
        return n.integral;
    }
    const uint32_t child = n.child;
    const double lower = integrate(child, floor, 0.5 * area);
    const double upper = integrate(child + 1, floor, 0.5 * area);
    directional_[node].integral = lower + upper;
    return lower + upper;
}

uint64_t GuidingTree::update() {
    if (!counters_) return 0;  // learning stopped
    uint64_t records = 0;
    // Fold every region and its directional leaves; list the leaves and regions that took records.
    std::vector<uint32_t> split_regions, split_cells;
    std::vector<Box> region_boxes;
    std::vector<std::array<double, 2>> cell_sides;
    {
        std::vector<std::pair<uint32_t, Box>> stack{{0, Box{{0, 0, 0}, {1, 1, 1}}}};
        while (!stack.empty()) {
            const auto [node, box] = stack.back();
            stack.pop_back();
            const SpatialNode& n = spatial_[node];
            if (n.child != 0) {
                Box lower = box, upper = box;
                lower.hi[n.axis] = upper.lo[n.axis] = 0.5 * (box.lo[n.axis] + box.hi[n.axis]);
                stack.push_back({n.child + 1, upper});
                stack.push_back({n.child, lower});
                continue;
            }
            const std::atomic<uint64_t>* c = counters_of_spatial(node);
            uint64_t count = 0, units = 0;
            for (size_t k = 0; k < kSpatialCounters; k += 2) {
                count += c[k].load(std::memory_order_relaxed);
                units += c[k + 1].load(std::memory_order_relaxed);
            }
            records += count;
            if (count == 0 || count > kMaxPassRecords) continue;
            spatial_[node].totals.count += static_cast<double>(count);
            spatial_[node].totals.sum += static_cast<double>(units) / kUnitsPerLuminance;
            double st_box[4] = {0.0, 1.0, 0.0, 1.0};
            fold_directional(spatial_[node].directional_root, st_box, &split_cells, &cell_sides);
            split_regions.push_back(node);
            region_boxes.push_back(box);
        }
    }
    // Directional splits first, so a region splitting in the same update hands its halves the
    // refined distribution. Leaves split in the order listed (a fixed order: the tree's).
    for (size_t k = 0; k < split_cells.size(); ++k) {
        Histogram h;
        const std::atomic<uint64_t>* c = counters_of_directional(split_cells[k]);
        for (size_t b = 0; b < h.count.size(); ++b) {
            h.count[b] = static_cast<double>(c[2 * b].load(std::memory_order_relaxed));
            h.sum[b] = static_cast<double>(c[2 * b + 1].load(std::memory_order_relaxed)) / kUnitsPerLuminance;
        }
        refine_directional(split_cells[k], h, {0, kHistogramSide, 0, kHistogramSide}, cell_sides[k][0],
                           cell_sides[k][1]);
    }
    for (size_t k = 0; k < split_regions.size(); ++k) {
        SpatialHistogram h;
        const std::atomic<uint64_t>* c = counters_of_spatial(split_regions[k]);
        for (size_t b = 0; b < h.count.size(); ++b) {
            h.count[b] = static_cast<double>(c[2 * b].load(std::memory_order_relaxed));
            h.sum[b] = static_cast<double>(c[2 * b + 1].load(std::memory_order_relaxed)) / kUnitsPerLuminance;
        }
        const SpatialRange all{{0, 0, 0},
                               {kSpatialHistogramSide, kSpatialHistogramSide, kSpatialHistogramSide}};
        refine_spatial(split_regions[k], h, all, region_boxes[k], -1);
    }
    // p′ of every region anew: floors at a share of the region's mean radiance.
    for (uint32_t node = 0; node < spatial_.size(); ++node) {
        const SpatialNode& n = spatial_[node];
        if (n.child != 0) continue;
        const double mean = n.totals.count > 0.0 ? n.totals.sum / n.totals.count : 0.0;
        integrate(n.directional_root, kFloorFraction * mean, 1.0);
    }
    reset_counters();
    return records;
}

void GuidingTree::reset_counters() {
    size_t offset = 0;
    for (SpatialNode& n : spatial_) {
        n.counters = static_cast<uint32_t>(offset);
        if (n.child == 0) offset += kSpatialCounters;
    }
    for (DirectionalNode& n : directional_) {
        n.counters = static_cast<uint32_t>(offset);
        if (n.child == 0) offset += kDirectionalCounters;
    }
    counter_count_ = offset;
    // Value-initialised: every counter starts at 0.
    counters_ = std::make_unique<std::atomic<uint64_t>[]>(counter_count_);
}

void GuidingTree::stop_learning() {
    counters_.reset();
    counter_count_ = 0;
}

}  // namespace stratum
