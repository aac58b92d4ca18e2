// The path-guiding 5-D tree (textbook §5, eq. 5.19): the incident radiance of the scene over
// (x_n, y_n, z_n, s, t), positions normalised to a padded cube around the scene and
// s = (cos θ + 1)/2, t = φ/2π of the world direction, so dω = 4π ds dt and every cell of the
// (s, t) square has a solid angle 4π × its area.
//
// Quantities:
// * region: a leaf of the spatial part (splits along x, y or z);
// * directional tree: each region's binary tree over (s, t); a region that splits gives both
//   halves a copy, counts scaled by their shares of its records;
// * L̃ of a directional leaf: the mean recorded luminance of its cell, floored at
//   kFloorFraction × the region's mean;
// * p′(s, t) = L̃(cell) / ∫ L̃ ds dt (5.19), piecewise constant; pdf in solid angle = p′ / 4π;
// * kSpatialThreshold, kDirectionalThreshold: records a region / a directional leaf holds
//   before it splits (the book's "threshold number of samples"). 4096 and 512: the least
//   variance of the thresholds tried (directional 32 to 2048, spatial 2048 to 16384) on a floor
//   under a small lamp and on a room lit through a door, 128² pixels, 32 training samples;
//   smaller leaves were worse, their L̃ resting on a few lucky paths.
//
// The tree is a kd-tree of the 5-D space in which the spatial splits lie above the directional
// ones (Müller et al. 2017's SD-tree has the same shape): then the distribution over directions
// at a point is one binary tree whose nodes hold their integrals, sampled by one descent.
// Split axis (GuidingSplit::Binary): spatially, the axis whose extent × balance of the records'
// halves is largest (a wall's records all lie in one half of its normal axis, which is not
// split); directionally, the axis whose halves' mean radiance differs most, the longer side of
// the cell when they agree. GuidingSplit::Full splits along every axis at once (the book's 32).
// Support: the floor keeps p′ > 0 for every direction of a region with recorded light, and a
// region without light is uniform over the sphere, so the guide alone covers every direction.
//
// Concurrency and determinism: within a render pass the structure is read-only; record() adds
// each record's count and fixed-point luminance into atomic integer counters of the leaves it
// lands in (integer addition is associative, so the totals do not depend on the order of the
// records or the thread count), and update(), between passes in one thread, folds them into the
// estimates and splits. A record's luminance is clamped to kMaxRecordLuminance (it shapes the
// guide only, never the estimate): at 2^-16 units a leaf holds 2^31 records per pass before a
// 64-bit sum could wrap, and a leaf past that count drops its pass (checked in update()).
#pragma once

#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "core/math.h"
#include "core/registry.h"

namespace stratum {

// How a node splits (textbook §5): in two along the one axis the records tell apart most
// (Binary, the book's binary split), or along every axis at once (Full, the book's 32 children:
// a region into 8 octants, each directional cell into 4 quadrants). Binary is the default: on a
// floor under a lamp, a room lit through a door and a diffuse Cornell box (128², 64 samples)
// Full gave the same variance within the noise of the measurement (0.97–1.24× Binary's) with
// 2.3–4.4× the nodes (175k nodes, 99 MB in the room).
// Menu order (default first): a host stores a choice by its position, so never reorder.
enum class GuidingSplit : uint8_t { Binary = 0, Full = 1 };
std::span<const RegistryEntry> guiding_split_choices();

class GuidingTree {
public:
    static constexpr uint32_t kSpatialThreshold = 4096;
    static constexpr uint32_t kDirectionalThreshold = 512;
    static constexpr float kFloorFraction = 0.01f;
    static constexpr float kMaxRecordLuminance = 65536.0f;
    // Depth limits: a directional cell of 2^-10 on a side (≈ 0.01 sr), spatial cells of 2^-12
    // of the cube's side per axis; and at most kMaxNodes nodes: 2^18 × (48 bytes, and 1 KiB of
    // counters per leaf while learning) ≤ 270 MiB while learning, 12 MiB after.
    static constexpr uint32_t kMaxDirectionalDepth = 20, kMaxSpatialDepth = 36;
    static constexpr size_t kMaxNodes = size_t{1} << 18;

    // The cube the positions are normalised to: centre ± half_side (padded by the caller).
    GuidingTree(Vec3 center, float half_side, GuidingSplit split = GuidingSplit::Binary);

    // The region (spatial leaf) holding point p; points outside the cube belong to the nearest.
    uint32_t region(Vec3 p) const;
    // A world direction drawn from p′ of `region` with (u.x, u.y) ∈ [0,1)², and its pdf in solid
    // angle (hierarchical warping: each binary choice rescales the coordinate of its axis).
    Vec3 sample(uint32_t region, Vec2 u, float* pdf) const;
    // The solid-angle pdf sample() gives `direction` (unit) in `region`, computed with the same
    // product of branch probabilities.
    float pdf(uint32_t region, Vec3 direction) const;

    // Thread-safe, order-independent: one estimate of the radiance arriving at `position` from
    // `direction` (luminance ≥ 0; not finite values are ignored).
    void record(Vec3 position, Vec3 direction, float luminance);
    // Between passes (no concurrent record or sample): folds the pass's records into the
    // estimates, splits the leaves past their thresholds, recomputes p′. Returns the records
    // the pass held.
    uint64_t update();
    // Releases the per-pass counters: record() ignores records from then on.
    void stop_learning();

    size_t node_count() const { return spatial_.size() + directional_.size(); }
    size_t region_count() const;
    // Bytes held: nodes and the per-pass counters.
    size_t bytes() const;

    // (s, t) of a unit direction and back (s = (cos θ + 1)/2, t = φ/2π, θ from +z).
    static Vec2 direction_to_st(Vec3 d);
    static Vec3 st_to_direction(double s, double t);

private:
    struct Totals {
        double count = 0, sum = 0;  // records and their summed luminance since the node was made
    };
    struct SpatialNode {
        uint32_t child = 0;  // first of two children (0: a leaf; the root is nobody's child)
        uint8_t axis = 0;    // 0, 1, 2 = x, y, z
        uint8_t depth = 0;
        uint32_t directional_root = 0;  // leaves: the root of the region's directional tree
        uint32_t counters = 0;          // leaves: offset of the pass counters
        Totals totals;
    };
    struct DirectionalNode {
        uint32_t child = 0;
        uint8_t axis = 0;  // 0 = s, 1 = t
        uint8_t depth = 0;
        uint32_t counters = 0;  // leaves: offset of the pass histogram
        double mean = 0;        // leaves: L̃, the floored mean luminance
        double integral = 0;    // ∫ L̃ ds dt over the node's cell
        Totals totals;
    };
    // Per-pass counters: records and luminance sum in each bin of a grid over the leaf's cell,
    // kSpatialHistogramSide³ over a region's box, kHistogramSide² over a directional leaf's
    // (s, t) cell, so one update can split a leaf several levels deep (a render trains in a
    // handful of passes: 1, 1, 2, 4, 8, 16 samples; one level per pass would leave 64 cells).
    static constexpr uint32_t kHistogramSide = 8;
    static constexpr uint32_t kSpatialHistogramSide = 4;
    static constexpr size_t kSpatialCounters =
        2 * kSpatialHistogramSide * kSpatialHistogramSide * kSpatialHistogramSide;
    static constexpr size_t kDirectionalCounters = 2 * kHistogramSide * kHistogramSide;
    // Fixed-point luminance units of the counters (2^31 records of kMaxRecordLuminance fit in
    // 63 bits).
    static constexpr double kUnitsPerLuminance = 65536.0;
    struct Box {
        double lo[3], hi[3];
    };
    // A directional leaf's pass histogram as numbers: count and luminance per bin (s-major).
    struct Histogram {
        std::array<double, kHistogramSide * kHistogramSide> count{}, sum{};
    };
    // Bins [i0, i1) × [j0, j1) of a histogram: a node's part of its leaf's cell.
    struct BinRange {
        uint32_t i0, i1, j0, j1;
    };
    // Records and luminance in a range of bins, and in the lower half of each axis of it.
    struct BinCounts {
        double count = 0, sum = 0;
        std::array<double, 2> lower_count{}, lower_sum{};
    };
    static BinCounts bin_counts(const Histogram& h, const BinRange& r);

    uint32_t descend_spatial(const double coords[3], Box* box) const;
    // The directional leaf one descent from a region's root reaches: its (s, t) cell
    // [cell[0], cell[1]) × [cell[2], cell[3]) and the product of the branch probabilities taken.
    struct DirectionalLeaf {
        uint32_t node;
        double cell[4];
        double probability;
        // p′ in the leaf as a solid-angle density: probability / cell area / 4π.
        double solid_angle_pdf() const;
    };
    // The one descent of a region's directional tree, which sample() (warping its numbers),
    // pdf() and record() (following a direction) all walk: at each node go_lower(axis, p_lower,
    // mid) chooses the lower child (probability p_lower, the children's integrals' share; its
    // cell ends at mid along axis) or the upper.
    template <typename GoLower>
    DirectionalLeaf descend_directional(uint32_t root, GoLower&& go_lower) const;
    // The leaf whose cell holds (s, t) = st.
    DirectionalLeaf locate_directional(uint32_t root, Vec2 st) const;
    std::atomic<uint64_t>* counters_of_spatial(uint32_t node) const;
    std::atomic<uint64_t>* counters_of_directional(uint32_t node) const;
    // Splits `node` while its records pass the threshold, by the split rule, from the pass's
    // records in the bins `r` of its leaf's histogram (its cell's part of it).
    void refine_directional(uint32_t node, const Histogram& h, const BinRange& r, double cell_s,
                            double cell_t);
    // Splits `node` in two along `axis`; the children's totals are the parent's times the lower
    // half's share of the records in `c`. Returns the lower child.
    uint32_t halve_directional(uint32_t node, uint8_t axis, const BinCounts& c);
    struct SpatialHistogram {
        std::array<double, kSpatialHistogramSide * kSpatialHistogramSide * kSpatialHistogramSide> count{},
            sum{};
    };
    // Bins [lo, hi) per axis of a region's histogram: a node's part of its leaf's box.
    struct SpatialRange {
        uint32_t lo[3], hi[3];
    };
    struct SpatialCounts {
        double count = 0, sum = 0;
        std::array<double, 3> lower_count{}, lower_sum{};
    };
    static SpatialCounts spatial_counts(const SpatialHistogram& h, const SpatialRange& r);
    // Splits region `node` while it passes the threshold, from the pass's records in the bins
    // `r` of its leaf's histogram; `forced_axis` ≥ 0: the split into octants continues there.
    void refine_spatial(uint32_t node, const SpatialHistogram& h, const SpatialRange& r, const Box& box,
                        int forced_axis);
    // Splits `node` in two along `axis` (false past kMaxNodes); the halves' totals are the
    // parent's times the lower half's share of the records in `c`.
    bool halve_spatial(uint32_t node, int axis, const SpatialCounts& c);
    // Copies the directional subtree at `from` into the slot `to`, totals scaled by `share`.
    void copy_directional(uint32_t from, uint32_t to, double share);
    void scale_directional(uint32_t node, double share);
    // Folds the pass histograms of the leaves under `node` into their totals; lists the leaves
    // that took records with their cells' sides.
    void fold_directional(uint32_t node, double st_box[4], std::vector<uint32_t>* to_split,
                          std::vector<std::array<double, 2>>* sides);
    // Recomputes the leaves' floored means and every node's integral under `node`; returns it.
    double integrate(uint32_t node, double floor, double area);
    void reset_counters();

    Vec3 lo_;
    float side_;
    GuidingSplit split_;
    std::vector<SpatialNode> spatial_;
    std::vector<DirectionalNode> directional_;
    // The pass counters of the leaves at the last reset (offsets in the nodes).
    std::unique_ptr<std::atomic<uint64_t>[]> counters_;
    size_t counter_count_ = 0;
};

}  // namespace stratum
