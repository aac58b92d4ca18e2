#include "guiding/guiding_tree.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace stratum {

namespace {

// Fixed-point luminance units of the per-pass counters (header: 2^31 records of the clamped
// maximum fit in 63 bits).
constexpr double kUnitsPerLuminance = 65536.0;
constexpr uint64_t kMaxPassRecords = uint64_t{1} << 31;
// A leaf splits only on a pass that brought it this many records: the halves' counts then say
// something about where within the cell the records (and their radiance) lie.
constexpr uint64_t kMinPassRecordsToSplit = 16;
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

uint32_t GuidingTree::descend_directional(uint32_t node, double s, double t, double st_box[4]) const {
    st_box[0] = 0.0, st_box[1] = 1.0, st_box[2] = 0.0, st_box[3] = 1.0;
    while (directional_[node].child != 0) {
        const uint8_t a = directional_[node].axis;
        const double v = a == 0 ? s : t;
        double* lo = &st_box[2 * a];
        const double mid = 0.5 * (lo[0] + lo[1]);
        if (v < mid) {
            lo[1] = mid;
            node = directional_[node].child;
        } else {
            lo[0] = mid;
            node = directional_[node].child + 1;
        }
    }
    return node;
}

uint32_t GuidingTree::region(Vec3 p) const {
    double coords[3];
    for (int a = 0; a < 3; ++a) coords[a] = clamp_unit((static_cast<double>(p[a]) - lo_[a]) / side_);
    Box box;
    return descend_spatial(coords, &box);
}

Vec3 GuidingTree::sample(uint32_t region, Vec2 u, float* pdf) const {
    uint32_t node = spatial_[region].directional_root;
    if (!(directional_[node].integral > 0.0)) {
        *pdf = kInv4Pi;
        return st_to_direction(clamp_unit(u.x), clamp_unit(u.y));
    }
    double uv[2] = {clamp_unit(u.x), clamp_unit(u.y)};
    double box[4] = {0.0, 1.0, 0.0, 1.0};
    double probability = 1.0;
    while (directional_[node].child != 0) {
        const DirectionalNode& n = directional_[node];
        const uint8_t a = n.axis;
        const double p_lower =
            lower_probability(directional_[n.child].integral, directional_[n.child + 1].integral);
        const double mid = 0.5 * (box[2 * a] + box[2 * a + 1]);
        if (uv[a] < p_lower) {
            uv[a] = clamp_unit(uv[a] / p_lower);
            probability *= p_lower;
            box[2 * a + 1] = mid;
            node = n.child;
        } else {
            uv[a] = clamp_unit((uv[a] - p_lower) / (1.0 - p_lower));
            probability *= 1.0 - p_lower;
            box[2 * a] = mid;
            node = n.child + 1;
        }
    }
    const double area = (box[1] - box[0]) * (box[3] - box[2]);
    *pdf = static_cast<float>(probability / area * kInv4Pi);
    return st_to_direction(box[0] + uv[0] * (box[1] - box[0]), box[2] + uv[1] * (box[3] - box[2]));
}

float GuidingTree::pdf(uint32_t region, Vec3 direction) const {
    uint32_t node = spatial_[region].directional_root;
    if (!(directional_[node].integral > 0.0)) return kInv4Pi;
    const Vec2 st = direction_to_st(direction);
    const double v[2] = {st.x, st.y};
    double box[4] = {0.0, 1.0, 0.0, 1.0};
    double probability = 1.0;
    while (directional_[node].child != 0) {
        const DirectionalNode& n = directional_[node];
        const uint8_t a = n.axis;
        const double p_lower =
            lower_probability(directional_[n.child].integral, directional_[n.child + 1].integral);
        const double mid = 0.5 * (box[2 * a] + box[2 * a + 1]);
        if (v[a] < mid) {
            probability *= p_lower;
            box[2 * a + 1] = mid;
            node = n.child;
        } else {
            probability *= 1.0 - p_lower;
            box[2 * a] = mid;
            node = n.child + 1;
        }
    }
    const double area = (box[1] - box[0]) * (box[3] - box[2]);
    return static_cast<float>(probability / area * kInv4Pi);
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
    double st_box[4];
    const uint32_t cell = descend_directional(spatial_[leaf].directional_root, st.x, st.y, st_box);
    const auto bin = [](double v, double lo, double hi) {
        return std::min(kHistogramSide - 1, static_cast<uint32_t>((v - lo) / (hi - lo) * kHistogramSide));
    };
    const uint32_t b = bin(st.x, st_box[0], st_box[1]) * kHistogramSide + bin(st.y, st_box[2], st_box[3]);
    c = counters_of_directional(cell) + 2 * b;
    c[0].fetch_add(1, std::memory_order_relaxed);
    c[1].fetch_add(units, std::memory_order_relaxed);
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

size_t GuidingTree::region_count() const {
    return static_cast<size_t>(
        std::count_if(spatial_.begin(), spatial_.end(), [](const SpatialNode& n) { return n.child == 0; }));
}

size_t GuidingTree::bytes() const {
    return spatial_.size() * sizeof(SpatialNode) + directional_.size() * sizeof(DirectionalNode) +
           counter_count_ * sizeof(std::atomic<uint64_t>);
}

}  // namespace stratum
