#include "film/error_estimate.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace stratum {

// Along rows, then along columns (separable), by running sums: O(1) per pixel whatever r.
std::vector<double> box_sum(const std::vector<double>& v, uint32_t width, uint32_t height, uint32_t r) {
    std::vector<double> rows(v.size(), 0.0), out(v.size(), 0.0);
    const auto window = [r](uint32_t i, uint32_t n) {
        return std::pair{i >= r ? i - r : 0u, std::min(n - 1, i + r)};
    };
    std::vector<double> prefix(std::max(width, height) + 1, 0.0);
    for (uint32_t y = 0; y < height; ++y) {
        const double* in = &v[static_cast<size_t>(y) * width];
        for (uint32_t x = 0; x < width; ++x) prefix[x + 1] = prefix[x] + in[x];
        for (uint32_t x = 0; x < width; ++x) {
            const auto [lo, hi] = window(x, width);
            rows[static_cast<size_t>(y) * width + x] = prefix[hi + 1] - prefix[lo];
        }
    }
    for (uint32_t x = 0; x < width; ++x) {
        for (uint32_t y = 0; y < height; ++y)
            prefix[y + 1] = prefix[y] + rows[static_cast<size_t>(y) * width + x];
        for (uint32_t y = 0; y < height; ++y) {
            const auto [lo, hi] = window(y, height);
            out[static_cast<size_t>(y) * width + x] = prefix[hi + 1] - prefix[lo];
        }
    }
    return out;
}

void estimate_pixel_errors(const PixelRegion& region, std::span<const PrefixMeans> prefixes,
                           std::span<PixelErrorEstimate> out) {
    const size_t pixels = region.pixel_count();
    // f from Σ_c d1² and Σ_c d2² of the pixels that have both, pooled.
    std::vector<double> d1_sq(pixels, 0.0), d2_sq(pixels, 0.0);
    for (size_t p = 0; p < pixels; ++p) {
        const PrefixMeans& m = prefixes[p];
        if (m.levels < 3) continue;
        for (uint32_t c = 0; c < 3; ++c) {
            const double d1 = m.mean[0][c] - m.mean[1][c], d2 = m.mean[1][c] - m.mean[2][c];
            d1_sq[p] += d1 * d1;
            d2_sq[p] += d2 * d2;
        }
    }
    const std::vector<double> pooled_d1 = box_sum(d1_sq, region.width, region.height, kSharePoolRadius);
    const std::vector<double> pooled_d2 = box_sum(d2_sq, region.width, region.height, kSharePoolRadius);
    // Each pixel's V_P and s²/P (channels summed), pooled into G.
    std::vector<double> prefix_variance(pixels, 0.0), iid_variance(pixels, 0.0);
    for (size_t p = 0; p < pixels; ++p) {
        const PrefixMeans& m = prefixes[p];
        if (m.levels < 2) continue;
        // f: the share of E d1² that falls as 1/m (the rest as 1/m³), pooled; 1 without a
        // second level or any spread.
        double f = 1.0;
        if (m.levels == 3 && pooled_d1[p] > 0.0)
            f = std::clamp((8.0 * pooled_d1[p] - pooled_d2[p]) / (6.0 * pooled_d1[p]), 0.0, 1.0);
        const double to_variance = f + (1.0 - f) / 7.0;
        for (uint32_t c = 0; c < 3; ++c) {
            const double d1 = m.mean[0][c] - m.mean[1][c];
            double v = d1 * d1 * to_variance;
            if (m.levels == 3) {
                const double d2 = m.mean[1][c] - m.mean[2][c];
                v = 0.5 * (v + d2 * d2 / (2.0 * f + 8.0 * (1.0 - f)) * to_variance);
            }
            prefix_variance[p] += v;
        }
        iid_variance[p] = m.iid_variance;
    }
    const std::vector<double> pooled_prefix =
        box_sum(prefix_variance, region.width, region.height, kPoolRadius);
    const std::vector<double> pooled_iid = box_sum(iid_variance, region.width, region.height, kPoolRadius);
    for (size_t p = 0; p < pixels; ++p) {
        PixelErrorEstimate& e = out[p];
        e = PixelErrorEstimate{};
        if (prefixes[p].levels < 2) continue;
        e.count = prefixes[p].count;
        // No spread around the pixel at all: nothing to correct, G = 1.
        if (pooled_iid[p] > 0.0) e.gain = static_cast<float>(pooled_prefix[p] / pooled_iid[p]);
    }
}

}  // namespace stratum
